#include "uampc/runtime/yaml_errors.hpp"

#include <yaml-cpp/yaml.h>

#include <map>

#include "uampc/runtime/edit_distance.hpp"
#include "yaml_walk.hpp"

namespace uampc {

namespace {

// Problems of one mapping's keys.
void checkMappingKeys(const YAML::Node& map, const std::string& file, std::vector<std::string>& errors) {
  std::map<std::string, YAML::Node> seen;
  for (const auto& kv : map) {
    const std::string where = YamlErrors::locationIn(file, kv.first).str();
    if (!kv.first.IsScalar()) {
      errors.push_back(where + ": error: a key must be a plain name, not a " +
                       (kv.first.IsSequence() ? "list"
                        : kv.first.IsMap()    ? "mapping"
                                              : "null"));
      continue;
    }
    const auto [first, inserted] = seen.emplace(kv.first.Scalar(), kv.first);
    if (!inserted) {
      errors.push_back(where + ": error: key '" + kv.first.Scalar() + "' is written twice in this mapping (first at " +
                       YamlErrors::locationIn(file, first->second).str() + ")");
    }
  }
}

}  // namespace

std::vector<std::string> yamlStructureErrors(const YAML::Node& root, const std::string& file) {
  std::vector<std::string> errors;
  forEachNodeOnce(root, [&](const YAML::Node& node) {
    if (node.IsMap()) checkMappingKeys(node, file, errors);
  });
  return errors;
}

SourceLocation YamlErrors::locationIn(const std::string& file, const YAML::Node& node) {
  const YAML::Mark m = node.Mark();
  if (m.is_null()) return {file, 0, 0};
  return {file, m.line + 1, m.column + 1};
}

void YamlErrors::add(const SourceLocation& where, const std::string& message) {
  messages_.push_back(where.str() + ": error: " + message);
}

void YamlErrors::checkKeys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what) {
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    if (allowed.count(key)) continue;
    const std::string guess = closestMatch(key, {allowed.begin(), allowed.end()});
    std::string hint;
    if (!guess.empty()) {
      hint = "; did you mean '" + guess + "'?";
    } else if (!allowed.empty()) {
      for (const auto& a : allowed) hint += (hint.empty() ? " (allowed: " : ", ") + a;
      hint += ")";
    }
    add(kv.first, "unknown key '" + key + "' in " + what + hint);
  }
}

}  // namespace uampc
