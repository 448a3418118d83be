#include "yaml_walk.hpp"

#include <set>
#include <utility>
#include <vector>

namespace uampc {

void forEachNodeOnce(const YAML::Node& root, const std::function<void(const YAML::Node&)>& visit) {
  // A collection's place in its file identifies it: its aliases share it. (Nodes built in code have
  // no place; they are visited as often as they appear.)
  std::set<std::pair<int, int>> visited;
  std::vector<YAML::Node> pending{root};
  while (!pending.empty()) {
    const YAML::Node node = pending.back();
    pending.pop_back();
    const bool collection = node.IsMap() || node.IsSequence();
    if (collection && !node.Mark().is_null() && !visited.insert({node.Mark().line, node.Mark().column}).second) {
      continue;
    }
    visit(node);
    if (node.IsMap()) {
      for (const auto& kv : node) {
        pending.push_back(kv.first);
        pending.push_back(kv.second);
      }
    } else if (node.IsSequence()) {
      for (const auto& item : node) pending.push_back(item);
    }
  }
}

}  // namespace uampc
