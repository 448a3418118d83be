#include "uampc/runtime/yaml_errors.hpp"

#include <yaml-cpp/yaml.h>

#include <map>
#include <set>

#include "uampc/runtime/edit_distance.hpp"

namespace uampc {

namespace {

// A collection's place in its file: aliases of it share it, so it identifies the collection.
std::pair<int, int> placeOf(const YAML::Node& node) { return {node.Mark().line, node.Mark().column}; }

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
  std::set<std::pair<int, int>> visited;
  std::vector<YAML::Node> pending{root};  // a stack, not recursion: deep nesting must not overflow
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    if (!node.IsMap() && !node.IsSequence()) continue;
    if (!node.Mark().is_null() && !visited.insert(placeOf(node)).second) continue;
    if (node.IsMap()) {
      checkMappingKeys(node, file, errors);
      for (const auto& kv : node) pending.push_back(kv.second);
    } else {
      for (const auto& item : node) pending.push_back(item);
    }
  }
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
