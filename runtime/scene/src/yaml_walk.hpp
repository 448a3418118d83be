// Every node of a parsed YAML document, each collection once however often it is aliased: an
// alias bomb (ten aliases of ten aliases ... nine levels deep, 10^9 nodes if expanded) costs what
// its text costs. A stack, not recursion, so deep nesting cannot overflow ours.
#pragma once

#include <yaml-cpp/yaml.h>

#include <functional>

namespace uampc {

// Calls `visit` for the root and every key and value below it.
void forEachNodeOnce(const YAML::Node& root, const std::function<void(const YAML::Node&)>& visit);

}  // namespace uampc
