#include "uampc/runtime/yaml_errors.hpp"

#include <yaml-cpp/yaml.h>

#include "uampc/runtime/edit_distance.hpp"

namespace uampc {

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
