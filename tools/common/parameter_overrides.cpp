#include "parameter_overrides.hpp"

#include <stdexcept>

#include "uampc/runtime/edit_distance.hpp"
#include "uampc/runtime/parameter_text.hpp"

namespace uampc::tools {

ParameterOverrides::ParameterOverrides(const std::vector<std::string>& assignments) {
  for (const std::string& text : assignments) {
    const auto dot = text.find('.'), equals = text.find('=');
    if (dot == std::string::npos || equals == std::string::npos || dot > equals || dot == 0 || equals == dot + 1) {
      throw std::invalid_argument("--set " + text + ": expected " + kSyntax + " (e.g. lo.scan_voxel_size=0.15)");
    }
    assignments_.push_back(
        {text, text.substr(0, dot), text.substr(dot + 1, equals - dot - 1), text.substr(equals + 1), false});
  }
}

std::map<std::string, ParameterValue> ParameterOverrides::valuesFor(const std::string& group,
                                                                    const ComponentSpec& spec) {
  std::vector<std::string> names;
  for (const auto& p : spec.parameters()) names.push_back(p.name);
  std::map<std::string, ParameterValue> values;
  for (Assignment& a : assignments_) {
    if (a.group != group) continue;
    a.used = true;
    const ParameterSpec* declared = spec.findParameter(a.name);
    if (!declared) {
      const std::string guess = closestMatch(a.name, names);
      throw std::invalid_argument("--set " + a.text + ": no parameter '" + a.name + "' in " + group +
                                  (guess.empty() ? "" : "; did you mean '" + group + "." + guess + "'?"));
    }
    try {
      values[a.name] = parseParameterValue(*declared, a.value);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--set " + a.text + ": " + e.what());
    }
  }
  return values;
}

void ParameterOverrides::checkAllUsed() const {
  for (const Assignment& a : assignments_) {
    if (!a.used) throw std::invalid_argument("--set " + a.text + ": no group '" + a.group + "' in this tool");
  }
}

}  // namespace uampc::tools
