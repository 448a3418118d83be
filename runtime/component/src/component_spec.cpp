#include "uampc/runtime/component_spec.hpp"

#include <stdexcept>

namespace uampc {

PortSpec& ComponentSpec::addPort(PortSpec port) {
  if (findPort(port.name)) throw std::logic_error(type + ": port '" + port.name + "' declared twice");
  ports_.push_back(std::move(port));
  return ports_.back();
}

ParameterSpec& ComponentSpec::addParameter(ParameterSpec parameter) {
  if (findParameter(parameter.name)) {
    throw std::logic_error(type + ": parameter '" + parameter.name + "' declared twice");
  }
  parameters_.push_back(std::move(parameter));
  return parameters_.back();
}

ParameterSpec& ComponentSpec::param(const std::string& name, bool value, const std::string& doc) {
  return addParameter({name, ParameterType::kBool, ParameterValue(value), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::param(const std::string& name, int value, const std::string& doc) {
  return addParameter({name, ParameterType::kInt, ParameterValue(static_cast<std::int64_t>(value)), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::param(const std::string& name, double value, const std::string& doc) {
  return addParameter({name, ParameterType::kDouble, ParameterValue(value), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::param(const std::string& name, const char* value, const std::string& doc) {
  return addParameter({name, ParameterType::kString, ParameterValue(std::string(value)), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::param(const std::string& name, std::vector<double> value, const std::string& doc) {
  return addParameter({name, ParameterType::kDoubleList, ParameterValue(std::move(value)), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::stringListParam(const std::string& name, std::vector<std::string> value,
                                              const std::string& doc) {
  return addParameter({name, ParameterType::kStringList, ParameterValue(std::move(value)), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::pathParam(const std::string& name, const std::string& value, const std::string& doc) {
  return addParameter({name, ParameterType::kPath, ParameterValue(value), doc, {}, {}, {}});
}
ParameterSpec& ComponentSpec::requiredParam(const std::string& name, ParameterType type, const std::string& doc) {
  return addParameter({name, type, std::nullopt, doc, {}, {}, {}});
}

const PortSpec* ComponentSpec::findPort(const std::string& name) const {
  for (const auto& p : ports_) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

const ParameterSpec* ComponentSpec::findParameter(const std::string& name) const {
  for (const auto& p : parameters_) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace uampc
