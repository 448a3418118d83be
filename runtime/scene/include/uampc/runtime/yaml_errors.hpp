// Every problem of a YAML file (a scene, an experiment) collected, so that one invocation reports
// them all, each as "file:line:column: error: message".
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "uampc/runtime/scene.hpp"  // SourceLocation

namespace YAML {
class Node;
}

namespace uampc {

// What yaml-cpp lets through in a parsed document but our readers cannot take: a key that is not a
// scalar (`? [a, b]`), and a key written twice in one mapping (yaml-cpp keeps both, and lookups
// then found the first or the last depending on how they were made). Each as
// "file:line:column: error: message"; empty when the document is sound. Aliased collections are
// checked once (yaml_walk.hpp).
std::vector<std::string> yamlStructureErrors(const YAML::Node& root, const std::string& file);

class YamlErrors {
 public:
  // Where a node is: its file, line and column, or what else names it (a --set override).
  using Locate = std::function<SourceLocation(const YAML::Node&)>;
  explicit YamlErrors(Locate locate) : locate_(std::move(locate)) {}

  // The parser's line and column of node in file; the file alone when the node has none.
  static SourceLocation locationIn(const std::string& file, const YAML::Node& node);

  void add(const SourceLocation& where, const std::string& message);
  void add(const YAML::Node& node, const std::string& message) { add(locate_(node), message); }
  // For every key of map that is not allowed: "unknown key 'K' in WHAT; did you mean 'G'?", or the
  // allowed keys when none is close.
  void checkKeys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what);

  bool empty() const { return messages_.empty(); }
  std::vector<std::string>& messages() { return messages_; }

 private:
  Locate locate_;
  std::vector<std::string> messages_;
};

}  // namespace uampc
