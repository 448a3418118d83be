// `--set GROUP.NAME=VALUE` for the development tools: the components' own parameters (their
// bindings: names, defaults, bounds, choices), applied to the cores' configs, so that a tool and a
// scene take a setting the same way:
//
//   tools::ParameterOverrides set(assignments);         // e.g. {"lo.scan_voxel_size=0.15"}
//   set.apply("lo", bindLoParameters, odometry_config);  // lo_parameters.hpp
//   set.checkAllUsed();                                  // a group nobody applied is an error
#pragma once

#include <string>
#include <vector>

#include "uampc/runtime/component_spec.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc::tools {

class ParameterOverrides {
 public:
  // Each "GROUP.NAME=VALUE"; throws std::invalid_argument naming one without a group or a value.
  explicit ParameterOverrides(const std::vector<std::string>& assignments);

  // Sets config's fields from the group's assignments through bind (declared first on a copy of
  // config, for the names, types and bounds). Throws std::invalid_argument naming the assignment
  // for an unknown name (with the closest known one) or a value its declaration refuses.
  template <typename Config>
  void apply(const std::string& group, void (*bind)(ParameterBinding&, Config&), Config& config) {
    ComponentSpec spec;
    Config declared = config;
    ParameterBinding declaring(spec);
    bind(declaring, declared);
    const auto values = valuesFor(group, spec);
    ParameterBinding reading(values);
    bind(reading, config);
  }

  // Throws std::invalid_argument naming an assignment whose group no apply() took.
  void checkAllUsed() const;

  // "GROUP.NAME=VALUE" for a tool's --help.
  static constexpr const char* kSyntax = "GROUP.NAME=VALUE";

 private:
  struct Assignment {
    std::string text, group, name, value;
    bool used = false;
  };
  std::map<std::string, ParameterValue> valuesFor(const std::string& group, const ComponentSpec& spec);

  std::vector<Assignment> assignments_;
};

}  // namespace uampc::tools
