// A scene file read with the files it extends: `extends: other.yaml` makes the scene the other
// scene with this file's keys deep-merged over it (docs/user/scenes.md, "One scene extending
// another"). The merged tree keeps the nodes of the files they were written in, so that every
// message can still name the file, line and column where a key or value was written.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace uampc {

class SceneDocument {
 public:
  // Reads `file` (absolute) and its extends chain; throws SceneError on YAML syntax errors, a
  // missing base file or an extends cycle.
  static SceneDocument load(const std::string& file);

  YAML::Node root;  // merged; no 'extends' key

  // The file a node of `root` was written in, or `fallback` for nodes made by the merge or by
  // command-line overrides.
  const std::string& fileOf(const YAML::Node& node, const std::string& fallback) const;

 private:
  void remember(const YAML::Node& node, const std::string& file);
  YAML::Node loadChain(const std::string& file, std::vector<std::string>& chain);

  // Every node of every file read, with its file, by the node's identity (nodeIdentity): a lookup
  // per location asked for, so that validating a scene stays linear in its size.
  std::unordered_map<const void*, std::string> origins_;
};

// `over` deep-merged over `base`: maps merged key by key, recursively; anything else replaced.
YAML::Node deepMerge(const YAML::Node& base, const YAML::Node& over);

}  // namespace uampc
