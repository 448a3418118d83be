#include "uampc/runtime/parameter_binding.hpp"

#include <cmath>

namespace uampc {

ParameterSpec& ParameterBinding::bind(const std::string& name, bool& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  field = context_->paramBool(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, int& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  field = static_cast<int>(context_->paramInt(name));  // the declared bounds keep it in range
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, double& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  field = context_->paramDouble(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, std::string& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field.c_str(), doc);
  field = context_->paramString(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, std::vector<double>& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  field = context_->paramDoubleList(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bindDegrees(const std::string& name, double& radians, const std::string& doc) {
  if (spec_) return spec_->param(name, radians * (180.0 / M_PI), doc);
  radians = context_->paramDouble(name) * M_PI / 180.0;
  return read_only_;
}

}  // namespace uampc
