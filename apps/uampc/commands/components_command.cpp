#include "commands/components_command.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli/command_set.hpp"
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
  return {{"name", port.name},
          {"direction", directionName(port.direction)},
          {"type", port.type_name},
          {"topic", port.default_topic},
          {"qos", toString(port.qos)},
          {"doc", port.doc},
          {"for_viewers", port.for_viewers}};
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
      if (param.min || param.max) std::cout << " in " << param.boundsText();
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

// A table cell: pipes escaped, line breaks folded, so that every text stays in its cell.
std::string markdownCell(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out;
}

std::string boundsAndChoices(const ParameterSpec& param) {
  std::string text = param.boundsText();
  if (!param.choices.empty()) {
    for (const auto& c : param.choices) text += (text.empty() ? "" : ", ") + ("`" + c + "`");
  }
  return text;
}

// docs/user/components.md: the same facts as the text listing, from the same declarations, without
// the libraries' paths (they differ from machine to machine), so the committed page can be checked
// against the binary (components_markdown_test).
void printMarkdown(const std::vector<const ComponentLibrary*>& libraries) {
  std::cout << "# Components\n\n"
               "Generated by `uampc components --markdown` from the components' own declarations (their\n"
               "parameter bindings): do not edit by hand. Each parameter is set in a scene under the\n"
               "component's `params:`, or with `--set NAME.parameter=value`; parameters marked *rig* are set\n"
               "once under the scene's `rig:` (docs/user/scenes.md). Units are SI unless the name says otherwise.\n";
  for (const auto* library : libraries) {
    const ComponentSpec& spec = library->spec();
    std::cout << "\n## " << spec.type << "\n\n" << spec.summary << ".\n";
    if (!spec.ports().empty() || spec.scenePortResolver()) {
      std::cout << "\n| port | direction | type | default topic | QoS | what |\n|---|---|---|---|---|---|\n";
      for (const auto& port : spec.ports()) {
        std::cout << "| " << port.name << " | " << directionName(port.direction) << " | `" << port.type_name << "` | `"
                  << port.default_topic << "` | " << toString(port.qos) << " | "
                  << markdownCell(port.doc + (port.for_viewers ? " (for viewers)" : "")) << " |\n";
      }
      if (spec.scenePortResolver()) std::cout << "\nPorts decided by the scene: " << spec.scenePortsDoc() << "\n";
    }
    if (spec.parameters().empty()) continue;
    std::cout << "\n| parameter | type | default | bounds | what |\n|---|---|---|---|---|\n";
    for (const auto& param : spec.parameters()) {
      const std::string value = param.required() ? "required" : "`" + toString(*param.default_value) + "`";
      std::cout << "| " << param.name << (param.rig ? " (*rig*)" : "") << " | " << toString(param.type) << " | "
                << markdownCell(value) << " | " << markdownCell(boundsAndChoices(param)) << " | "
                << markdownCell(param.doc) << " |\n";
    }
  }
}

}  // namespace

int componentsCommand(ComponentListFormat format) {
  ComponentCatalog catalog;
  std::vector<std::string> problems;
  const auto libraries = catalog.all(&problems);
  switch (format) {
    case ComponentListFormat::kJson:
      printJson(libraries);
      break;
    case ComponentListFormat::kMarkdown:
      printMarkdown(libraries);
      break;
    case ComponentListFormat::kText:
      printText(libraries);
      break;
  }
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

void addComponentsCommand(CommandSet& commands) {
  struct Options {
    bool json = false;
    bool markdown = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* sub = commands.add("components", "uampc components [--json | --markdown]",
                               "List installed component types with their ports and parameters.");
  CLI::Option* json = sub->add_flag("--json", options->json, "Print them as JSON (for tools) instead of text.");
  sub->add_flag("--markdown", options->markdown,
                "Print them as the Markdown page docs/user/components.md (without the libraries' paths).")
      ->excludes(json);
  commands.onRun(sub, [options] {
    return componentsCommand(options->json       ? ComponentListFormat::kJson
                             : options->markdown ? ComponentListFormat::kMarkdown
                                                 : ComponentListFormat::kText);
  });
}

}  // namespace uampc::app
