// `uampc graph SCENE.yaml [--set NAME=VALUE ...] [--format mermaid|dot]`: the scene's resolved
// graph (after extends, overrides and remapping), components as nodes, topics on the edges.
#pragma once

#include <string>
#include <vector>

#include "uampc/runtime/scene.hpp"

namespace uampc::app {

enum class GraphFormat { kMermaid, kDot };

// Every writer -> reader pair of a topic is one edge labelled with the topic and its type; a topic
// with no writer or no reader in the scene is a node of its own, drawn dashed.
std::string renderGraph(const Scene& scene, GraphFormat format);

int graphCommand(const std::vector<std::string>& args);

}  // namespace uampc::app
