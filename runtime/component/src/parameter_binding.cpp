#include "uampc/runtime/parameter_binding.hpp"

#include <cmath>

namespace uampc {

const ParameterValue* ParameterBinding::given(const std::string& name) const {
  const auto it = values_->find(name);
  return it == values_->end() ? nullptr : &it->second;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, bool& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  if (values_) {
    if (const ParameterValue* v = given(name)) field = std::get<bool>(*v);
    return read_only_;
  }
  field = context_->paramBool(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, int& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  if (values_) {
    if (const ParameterValue* v = given(name)) field = static_cast<int>(std::get<std::int64_t>(*v));
    return read_only_;
  }
  field = static_cast<int>(context_->paramInt(name));  // the declared bounds keep it in range
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, double& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  if (values_) {
    if (const ParameterValue* v = given(name)) field = std::get<double>(*v);
    return read_only_;
  }
  field = context_->paramDouble(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, std::string& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field.c_str(), doc);
  if (values_) {
    if (const ParameterValue* v = given(name)) field = std::get<std::string>(*v);
    return read_only_;
  }
  field = context_->paramString(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bind(const std::string& name, std::vector<double>& field, const std::string& doc) {
  if (spec_) return spec_->param(name, field, doc);
  if (values_) {
    if (const ParameterValue* v = given(name)) field = std::get<std::vector<double>>(*v);
    return read_only_;
  }
  field = context_->paramDoubleList(name);
  return read_only_;
}

ParameterSpec& ParameterBinding::bindDegrees(const std::string& name, double& radians, const std::string& doc) {
  if (spec_) return spec_->param(name, radians * (180.0 / M_PI), doc);
  if (values_) {
    if (const ParameterValue* v = given(name)) radians = std::get<double>(*v) * M_PI / 180.0;
    return read_only_;
  }
  radians = context_->paramDouble(name) * M_PI / 180.0;
  return read_only_;
}

}  // namespace uampc
