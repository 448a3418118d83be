// `uampc graph SCENE.yaml [--set NAME=VALUE ...] [--format mermaid|dot]`: the scene's resolved
// graph (after extends, overrides and remapping), components as nodes, topics on the edges.
#pragma once

#include <string>
#include <vector>

#include "uampc/runtime/launcher.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc::app {

enum class GraphFormat { kMermaid, kDot };

// Every writer -> reader pair of a topic is one edge labelled with the topic and its type; a topic
// with no writer or no reader in the scene is a node of its own, drawn dashed.
std::string renderGraph(const Scene& scene, GraphFormat format);

// Prints the graph of options.scene_path with options.overrides (the command line is parsed in
// main.cpp). Exit codes: 0, or 2 for an invalid scene.
int graphCommand(const LaunchOptions& options, GraphFormat format);

}  // namespace uampc::app
