// A component's parameters bound to the fields of its core's config, written once.
//
// One function lists the parameters (name, field, doc, bounds). describe() runs it on a default
// config to declare them, so each default is the core's own; the constructor runs it on a fresh
// config to fill it from the scene's values. A parameter can no longer be declared with one
// default in the component and have another in the core (it happened: mpc's panorama had drifted
// to 180 x 90 in the component while the core said 360 x 180).
//
//   static void bindParameters(ParameterBinding& b, lo::OdometryConfig& c) {
//     b.bind("scan_voxel_size", c.scan_voxel_size, "voxel downsampling of the scan, m").between(0.01, 10.0);
//   }
//   describe():  lo::OdometryConfig defaults;  ParameterBinding b(spec); bindParameters(b, defaults);
//   configFrom(): lo::OdometryConfig c;        ParameterBinding b(ctx);  bindParameters(b, c);
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "uampc/runtime/component.hpp"

namespace uampc {

class ParameterBinding {
 public:
  explicit ParameterBinding(ComponentSpec& spec) : spec_(&spec) {}           // declare, defaults from the fields
  explicit ParameterBinding(const Context& context) : context_(&context) {}  // read into the fields
  // Read the given values (checked, e.g. by parseParameterValue) into their fields; the others keep
  // theirs. The development tools apply `--set` this way to the cores' configs.
  explicit ParameterBinding(const std::map<std::string, ParameterValue>& values) : values_(&values) {}

  bool declaring() const { return spec_ != nullptr; }

  ParameterSpec& bind(const std::string& name, bool& field, const std::string& doc);
  ParameterSpec& bind(const std::string& name, int& field, const std::string& doc);
  ParameterSpec& bind(const std::string& name, double& field, const std::string& doc);
  ParameterSpec& bind(const std::string& name, std::string& field, const std::string& doc);
  ParameterSpec& bind(const std::string& name, std::vector<double>& field, const std::string& doc);
  // The field in radians, the parameter in degrees (as people write angles in a scene).
  ParameterSpec& bindDegrees(const std::string& name, double& radians, const std::string& doc);
  // An enum field written as one of the given names; the names are the parameter's choices.
  template <typename Enum>
  ParameterSpec& bindChoice(const std::string& name, Enum& field,
                            const std::vector<std::pair<std::string, Enum>>& names, const std::string& doc);

 private:
  // The value of `name` in values_, if it is there.
  const ParameterValue* given(const std::string& name) const;

  ComponentSpec* spec_ = nullptr;
  const Context* context_ = nullptr;
  const std::map<std::string, ParameterValue>* values_ = nullptr;
  // What bounds set while reading apply to: the scene loader checked them already.
  ParameterSpec read_only_;
};

template <typename Enum>
ParameterSpec& ParameterBinding::bindChoice(const std::string& name, Enum& field,
                                            const std::vector<std::pair<std::string, Enum>>& names,
                                            const std::string& doc) {
  if (spec_) {
    std::string default_name;
    std::vector<std::string> choices;
    for (const auto& [text, value] : names) {
      choices.push_back(text);
      if (value == field) default_name = text;
    }
    return spec_->param(name, default_name.c_str(), doc).oneOf(choices);
  }
  if (values_ && !given(name)) return read_only_;
  const std::string text = values_ ? std::get<std::string>(*given(name)) : context_->paramString(name);
  for (const auto& [choice, value] : names) {
    if (choice == text) field = value;
  }
  return read_only_;
}

}  // namespace uampc
