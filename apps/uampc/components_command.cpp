#include "components_command.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "uampc/run_files/json_text.hpp"
#include "uampc/runtime/component_library.hpp"

namespace uampc::app {

namespace {

// A parameter value as JSON: strings, booleans, integers, doubles and lists of doubles.
run_files::Json jsonValue(const ParameterValue& v) {
  return std::visit([](const auto& value) { return run_files::Json(value); }, v);
}

const char* directionName(PortDirection d) { return d == PortDirection::kInput ? "input" : "output"; }

run_files::Json portJson(const PortSpec& port) {
  return {{"name", port.name},         {"direction", directionName(port.direction)},
          {"type", port.type_name},    {"topic", port.default_topic},
          {"qos", toString(port.qos)}, {"doc", port.doc}, {"for_viewers", port.for_viewers}};
}

run_files::Json parameterJson(const ParameterSpec& param) {
  run_files::Json json = {{"name", param.name}, {"type", toString(param.type)}, {"required", param.required()}};
  if (param.default_value) json["default"] = jsonValue(*param.default_value);
  if (param.min) json["min"] = *param.min;
  if (param.max) json["max"] = *param.max;
  if (param.zero_is_off) json["zero_is_off"] = true;
  if (!param.choices.empty()) json["choices"] = param.choices;
  if (param.rig) json["rig"] = true;
  json["doc"] = param.doc;
  return json;
}

void printJson(const std::vector<const ComponentLibrary*>& libraries) {
  run_files::Json components = run_files::Json::array();
  for (const auto* library : libraries) {
    const ComponentSpec& spec = library->spec();
    run_files::Json ports = run_files::Json::array(), parameters = run_files::Json::array();
    for (const auto& port : spec.ports()) ports.push_back(portJson(port));
    for (const auto& param : spec.parameters()) parameters.push_back(parameterJson(param));
    run_files::Json component = {{"type", spec.type},
                                 {"summary", spec.summary},
                                 {"library", library->path()},
                                 {"ports", ports},
                                 {"parameters", parameters}};
    if (spec.scenePortResolver()) component["scene_ports"] = spec.scenePortsDoc();
    components.push_back(component);
  }
  std::cout << run_files::dumpJson(components) << "\n";
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
                << "[" << toString(port.qos) << "] " << port.doc << (port.for_viewers ? " (for viewers)" : "") << "\n";
    }
    if (spec.scenePortResolver()) std::cout << "  ports  decided by the scene: " << spec.scenePortsDoc() << "\n";
    const auto& parameters = spec.parameters();
    const int param_name = widest(parameters, [](const auto& p) { return p.name; });
    const int param_type = widest(parameters, [](const auto& p) { return std::string(toString(p.type)); });
    for (const auto& param : parameters) {
      std::cout << "  param  " << std::left << std::setw(param_name) << param.name << std::setw(param_type)
                << toString(param.type) << (param.required() ? "required" : "= " + toString(*param.default_value));
      if (param.min || param.max) {
        std::cout << " in [" << (param.min ? formatNumber(*param.min) : "-inf") << ", "
                  << (param.max ? formatNumber(*param.max) : "inf") << "]" << (param.zero_is_off ? " or 0 (off)" : "");
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
  if (json)
    printJson(libraries);
  else
    printText(libraries);
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
