#include "commands/graph_command.hpp"

#include <iostream>
#include <map>
#include <sstream>

namespace uampc::app {

namespace {

struct PortEnd {
  const ComponentInstance* instance;
  const PortSpec* port;
};

struct Topic {
  std::string name;
  std::string type;  // of the first port bound to it (a clash is a validation error)
  std::vector<PortEnd> writers, readers;
};

// Topics in order of first appearance (components in file order, ports in declaration order).
std::vector<Topic> topicsOf(const Scene& scene) {
  std::vector<Topic> topics;
  std::map<std::string, std::size_t> index;
  for (const auto& c : scene.components) {
    for (const auto& port : c.ports) {
      const std::string& name = c.topics.at(port.name);
      auto [it, added] = index.emplace(name, topics.size());
      if (added) topics.push_back({name, port.type_name, {}, {}});
      Topic& t = topics[it->second];
      (port.direction == PortDirection::kOutput ? t.writers : t.readers).push_back({&c, &port});
    }
  }
  return topics;
}

// Node ids: components by name (letters, digits, _) behind a prefix, so that no name collides
// with a keyword of either language (Mermaid's `end`, DOT's `node`); topics by number.
std::string componentId(const ComponentInstance& c) { return "c_" + c.name; }
std::string topicId(std::size_t i) { return "t" + std::to_string(i); }

void mermaid(const Scene& scene, const std::vector<Topic>& topics, std::ostream& out) {
  out << "flowchart LR\n";
  for (const auto& c : scene.components) {
    out << "  " << componentId(c) << "[\"" << c.name << "<br/>" << c.type << "<br/>process " << c.process << "\"]\n";
  }
  for (std::size_t i = 0; i < topics.size(); ++i) {
    const Topic& t = topics[i];
    const std::string label = t.name + "<br/>" + t.type;
    if (t.writers.empty() || t.readers.empty()) {
      out << "  " << topicId(i) << "([\"" << label << "<br/>(" << (t.writers.empty() ? "no writer" : "no reader")
          << ")\"])\n";
      for (const auto& w : t.writers) out << "  " << componentId(*w.instance) << " -.-> " << topicId(i) << "\n";
      for (const auto& r : t.readers) out << "  " << topicId(i) << " -.-> " << componentId(*r.instance) << "\n";
      continue;
    }
    for (const auto& w : t.writers) {
      for (const auto& r : t.readers) {
        out << "  " << componentId(*w.instance) << " -->|\"" << label << "\"| " << componentId(*r.instance) << "\n";
      }
    }
  }
}

void dot(const Scene& scene, const std::vector<Topic>& topics, std::ostream& out) {
  out << "digraph \"" << scene.name << "\" {\n  rankdir=LR;\n  node [shape=box];\n";
  for (const auto& c : scene.components) {
    out << "  " << componentId(c) << " [label=\"" << c.name << "\\n"
        << c.type << "\\nprocess " << c.process << "\"];\n";
  }
  for (std::size_t i = 0; i < topics.size(); ++i) {
    const Topic& t = topics[i];
    const std::string label = t.name + "\\n" + t.type;
    if (t.writers.empty() || t.readers.empty()) {
      out << "  " << topicId(i) << " [shape=ellipse, style=dashed, label=\"" << label << "\\n("
          << (t.writers.empty() ? "no writer" : "no reader") << ")\"];\n";
      for (const auto& w : t.writers)
        out << "  " << componentId(*w.instance) << " -> " << topicId(i) << " [style=dashed];\n";
      for (const auto& r : t.readers)
        out << "  " << topicId(i) << " -> " << componentId(*r.instance) << " [style=dashed];\n";
      continue;
    }
    for (const auto& w : t.writers) {
      for (const auto& r : t.readers) {
        out << "  " << componentId(*w.instance) << " -> " << componentId(*r.instance) << " [label=\"" << label
            << "\"];\n";
      }
    }
  }
  out << "}\n";
}

}  // namespace

std::string renderGraph(const Scene& scene, GraphFormat format) {
  std::ostringstream out;
  const std::vector<Topic> topics = topicsOf(scene);
  if (format == GraphFormat::kDot)
    dot(scene, topics, out);
  else
    mermaid(scene, topics, out);
  return out.str();
}

int graphCommand(const LaunchOptions& options, GraphFormat format) {
  ComponentCatalog catalog;
  try {
    const Scene scene = loadScene(options.scene_path, options.overrides, catalog);
    for (const auto& w : scene.warnings) std::cerr << w << "\n";
    std::cout << renderGraph(scene, format);
    return 0;
  } catch (const SceneError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    return 2;
  }
}

}  // namespace uampc::app
