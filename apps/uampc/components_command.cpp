#include "components_command.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "uampc/runtime/component_library.hpp"

namespace uampc::app {

namespace {

std::string jsonString(const std::string& s) {
  std::ostringstream out;
  out << '"';
  for (const char c : s) {
    switch (c) {
      case '"': out << "\\\""; break;
      case '\\': out << "\\\\"; break;
      case '\n': out << "\\n"; break;
      case '\t': out << "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << static_cast<int>(c) << std::dec;
        } else {
          out << c;
        }
    }
  }
  out << '"';
  return out.str();
}

std::string jsonValue(const ParameterValue& v) {
  if (auto* s = std::get_if<std::string>(&v)) return jsonString(*s);
  return toString(v);  // bool, numbers and lists print as valid JSON
}

const char* directionName(PortDirection d) { return d == PortDirection::kInput ? "input" : "output"; }

void printJson(const std::vector<const ComponentLibrary*>& libraries) {
  std::cout << "[\n";
  for (std::size_t i = 0; i < libraries.size(); ++i) {
    const ComponentSpec& spec = libraries[i]->spec();
    std::cout << "  {\"type\": " << jsonString(spec.type) << ", \"summary\": " << jsonString(spec.summary)
              << ", \"library\": " << jsonString(libraries[i]->path()) << ",\n   \"ports\": [";
    for (std::size_t p = 0; p < spec.ports().size(); ++p) {
      const PortSpec& port = spec.ports()[p];
      std::cout << (p ? ",\n     " : "\n     ") << "{\"name\": " << jsonString(port.name)
                << ", \"direction\": \"" << directionName(port.direction) << "\", \"type\": "
                << jsonString(port.type_name) << ", \"topic\": " << jsonString(port.default_topic)
                << ", \"qos\": \"" << toString(port.qos) << "\", \"doc\": " << jsonString(port.doc) << "}";
    }
    std::cout << "],\n   \"parameters\": [";
    for (std::size_t p = 0; p < spec.parameters().size(); ++p) {
      const ParameterSpec& param = spec.parameters()[p];
      std::cout << (p ? ",\n     " : "\n     ") << "{\"name\": " << jsonString(param.name) << ", \"type\": \""
                << toString(param.type) << "\", \"required\": " << (param.required() ? "true" : "false");
      if (param.default_value) std::cout << ", \"default\": " << jsonValue(*param.default_value);
      if (param.min) std::cout << ", \"min\": " << formatNumber(*param.min);
      if (param.max) std::cout << ", \"max\": " << formatNumber(*param.max);
      if (!param.choices.empty()) {
        std::cout << ", \"choices\": [";
        for (std::size_t c = 0; c < param.choices.size(); ++c) std::cout << (c ? ", " : "") << jsonString(param.choices[c]);
        std::cout << "]";
      }
      if (param.rig) std::cout << ", \"rig\": true";
      std::cout << ", \"doc\": " << jsonString(param.doc) << "}";
    }
    std::cout << "]}" << (i + 1 < libraries.size() ? "," : "") << "\n";
  }
  std::cout << "]\n";
}

void printText(const std::vector<const ComponentLibrary*>& libraries) {
  for (const auto* library : libraries) {
    const ComponentSpec& spec = library->spec();
    std::cout << spec.type << " - " << spec.summary << "\n  library: " << library->path() << "\n";
    // Columns as wide as their longest entry plus a space, so that long names never run together.
    auto widest = [](const auto& items, auto text) {
      int width = 0;
      for (const auto& item : items) width = std::max(width, static_cast<int>(text(item).size()));
      return width + 1;
    };
    const auto& ports = spec.ports();
    const int port_name = widest(ports, [](const auto& p) { return p.name; });
    const int port_type = widest(ports, [](const auto& p) { return p.type_name; });
    const int port_topic = widest(ports, [](const auto& p) { return p.default_topic; });
    for (const auto& port : ports) {
      std::cout << "  " << std::left << std::setw(7) << directionName(port.direction) << std::setw(port_name)
                << port.name << std::setw(port_type) << port.type_name << std::setw(port_topic) << port.default_topic
                << "[" << toString(port.qos) << "] " << port.doc << "\n";
    }
    const auto& parameters = spec.parameters();
    const int param_name = widest(parameters, [](const auto& p) { return p.name; });
    const int param_type = widest(parameters, [](const auto& p) { return std::string(toString(p.type)); });
    for (const auto& param : parameters) {
      std::cout << "  param  " << std::left << std::setw(param_name) << param.name << std::setw(param_type)
                << toString(param.type) << (param.required() ? "required" : "= " + toString(*param.default_value));
      if (param.min || param.max) {
        std::cout << " in [" << (param.min ? formatNumber(*param.min) : "-inf") << ", "
                  << (param.max ? formatNumber(*param.max) : "inf") << "]";
      }
      if (!param.choices.empty()) {
        std::cout << " one of";
        for (const auto& c : param.choices) std::cout << " " << c;
      }
      if (param.rig) std::cout << " (rig: set under rig:)";
      std::cout << "\n         " << param.doc << "\n";
    }
    std::cout << "\n";
  }
}

}  // namespace

int componentsCommand(bool json) {
  ComponentCatalog catalog;
  std::vector<std::string> problems;
  const auto libraries = catalog.all(&problems);
  if (json) printJson(libraries);
  else printText(libraries);
  for (const auto& p : problems) std::cerr << "uampc: " << p << "\n";
  if (libraries.empty()) {
    std::cerr << "uampc: no component libraries found in:";
    for (const auto& d : catalog.directories()) std::cerr << " " << d;
    std::cerr << "\n";
    return 1;
  }
  return problems.empty() ? 0 : 1;
}

int validateCommand(const LaunchOptions& options) {
  ComponentCatalog catalog;
  try {
    const Scene scene = loadScene(options.scene_path, options.overrides, catalog);
    for (const auto& w : scene.warnings) std::cerr << w << "\n";
    std::cout << options.scene_path << ": ok (" << scene.components.size() << " components in "
              << scene.processes().size() << " process(es))\n";
    return 0;
  } catch (const SceneError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    return 2;
  }
}

}  // namespace uampc::app
