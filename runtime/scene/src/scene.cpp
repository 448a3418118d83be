#include "uampc/runtime/scene.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <regex>
#include <set>
#include <sstream>

#include "scene_document.hpp"
#include "scene_ports.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/dds_security.hpp"
#include "uampc/runtime/edit_distance.hpp"
#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/lockstep_topics.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/yaml_errors.hpp"

namespace fs = std::filesystem;

namespace uampc {

std::string SourceLocation::str() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

static std::string joinLines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}

// Messages quote what the scene says; printable, so that a terminal shows them, not obeys them.
static std::vector<std::string> printable(std::vector<std::string> messages) {
  for (auto& m : messages) m = printableText(m);
  return messages;
}

SceneError::SceneError(std::vector<std::string> messages)
    : std::runtime_error(""), messages_(printable(std::move(messages))) {
  text_ = joinLines(messages_);
}

const char* SceneError::what() const noexcept { return text_.c_str(); }

std::vector<std::string> Scene::processes() const {
  std::vector<std::string> out;
  for (const auto& c : components) {
    if (std::find(out.begin(), out.end(), c.process) == out.end()) out.push_back(c.process);
  }
  return out;
}

bool Scene::processesStepThemselves() const { return clock.mode == ClockMode::kLockstep && clock.in_process; }

// DDS readers of a topic: in each process, the typed inputs with one QoS share one reader
// (launch/src/process/context_impl.cpp); each serialized input has its own.
int Scene::readersOf(const std::string& topic) const {
  std::set<std::pair<std::string, QosPreset>> shared;
  int own = 0;
  for (const auto& c : components) {
    for (const auto& port : c.ports) {
      if (port.direction != PortDirection::kInput || c.topics.at(port.name) != topic) continue;
      if (port.serialized)
        ++own;
      else
        shared.insert({c.process, port.qos});
    }
  }
  return static_cast<int>(shared.size()) + own;
}

int Scene::writersOf(const std::string& topic) const {
  int n = 0;
  for (const auto& c : components) {
    for (const auto& port : c.ports) {
      if (port.direction == PortDirection::kOutput && c.topics.at(port.name) == topic) ++n;
    }
  }
  return n;
}

const PortSpec* ComponentInstance::findPort(const std::string& port) const {
  for (const auto& p : ports) {
    if (p.name == port) return &p;
  }
  return nullptr;
}

const ComponentInstance* Scene::find(const std::string& name) const {
  for (const auto& c : components) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

Override parseOverride(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw SceneError({"--set " + text + ": error: expected NAME=VALUE, e.g. motor.encoder_rate=100"});
  }
  Override o{text, {}, text.substr(eq + 1)};
  std::stringstream keys(text.substr(0, eq));
  for (std::string part; std::getline(keys, part, '.');) {
    if (part.empty()) throw SceneError({"--set " + text + ": error: empty name between dots"});
    o.path.push_back(part);
  }
  return o;
}

namespace {

// Component and process names become DDS participant names, log prefixes and file names; a process
// name of 250 characters stalled the start for 60 s. 63 is far more than a name needs.
constexpr std::size_t kMaxNameLength = 63;
constexpr double kMinRealTimeFactor = 0.001;

// A ROS 2 topic name, as the scene's `topics:` and `external_topics:` take it.
const std::regex& topicPattern() {
  static const std::regex pattern("(/[A-Za-z_][A-Za-z0-9_]*)+");
  return pattern;
}

// Collects errors so that one run of the validator reports every problem in the file.
class SceneValidator {
 public:
  SceneValidator(std::string file, const SceneDocument& document, ComponentCatalog& catalog)
      : file_(std::move(file)), document_(document), catalog_(catalog) {}

  Scene validate(YAML::Node root, const std::vector<Override>& overrides);
  bool check_security_ = true;  // false: security.directory is only read (`uampc security init` makes it)

 private:
  SourceLocation at(const YAML::Node& node) const {
    const YAML::Mark m = node.Mark();
    if (m.is_null()) return {file_, 0, 0};
    return {document_.fileOf(node, file_), m.line + 1, m.column + 1};
  }
  // Relative paths are relative to the file they were written in (a base scene's, for what it
  // sets); those given on the command line, to the scene's.
  std::string directoryOf(const YAML::Node& node) const {
    for (const auto& override_node : override_nodes_) {
      if (override_node.first.is(node)) return fs::path(file_).parent_path().string();
    }
    return fs::path(document_.fileOf(node, file_)).parent_path().string();
  }
  void error(const SourceLocation& where, const std::string& message) { collector_.add(where, message); }
  void error(const YAML::Node& node, const std::string& message) { error(locationOf(node), message); }
  SourceLocation locationOf(const YAML::Node& node) const {
    for (const auto& [override_node, text] : override_nodes_) {
      if (override_node.is(node)) return {"--set " + text, 0, 0};
    }
    // Keys created by an override have no position in the file: name the override instead.
    if (node.Mark().is_null() && node.IsScalar()) {
      for (const auto& [key, text] : override_keys_) {
        if (key == node.Scalar()) return {"--set " + text, 0, 0};
      }
    }
    return at(node);
  }

  void checkKeys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what) {
    collector_.checkKeys(map, allowed, what);
  }
  void applyOverrides(YAML::Node& root, const std::vector<Override>& overrides);
  void readTopLevel(const YAML::Node& root, Scene& scene);
  void readClock(const YAML::Node& node, Scene& scene);
  void readTopicList(const YAML::Node& node, const std::string& key, std::vector<std::string>& topics);
  void readSecurity(const YAML::Node& node, Scene& scene);
  void readComponent(const YAML::Node& key, const YAML::Node& node, Scene& scene);
  void readParameters(const YAML::Node& node, ComponentInstance& instance, const ComponentSpec& spec, Scene& scene);
  void checkRequirements(const YAML::Node& params, const ComponentInstance& instance, const ComponentSpec& spec);
  std::optional<ParameterValue> readValue(const YAML::Node& node, const ParameterSpec& spec, const std::string& owner);
  void readTopics(const YAML::Node& node, ComponentInstance& instance, const ComponentSpec& spec,
                  std::vector<PortReference>& references);
  std::string resolvePath(const std::string& value, const std::string& directory) const;

  template <typename T>
  std::optional<T> scalar(const YAML::Node& node, const std::string& what) {
    if (!node.IsScalar()) {
      error(node, what + " must be a single value");
      return std::nullopt;
    }
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      error(node, what + ": cannot read '" + node.Scalar() + "' as " + typeWord<T>());
      return std::nullopt;
    }
  }
  template <typename T>
  static const char* typeWord() {
    if constexpr (std::is_same_v<T, bool>)
      return "true or false";
    else if constexpr (std::is_unsigned_v<T>)
      return "a whole number of 0 or more";
    else if constexpr (std::is_integral_v<T>)
      return "an integer";
    else if constexpr (std::is_floating_point_v<T>)
      return "a number";
    else
      return "a string";
  }

  std::string file_;
  const SceneDocument& document_;
  ComponentCatalog& catalog_;
  YamlErrors collector_{[this](const YAML::Node& node) { return locationOf(node); }};
  std::vector<std::string>& errors_ = collector_.messages();        // also filled by scene_ports.cpp
  std::vector<std::pair<YAML::Node, std::string>> override_nodes_;  // value grafted by --set, its text
  std::vector<std::pair<std::string, std::string>> override_keys_;  // last name of each --set, its text
  std::vector<PortReference> pending_;
  std::set<std::string> component_names_;                         // of scene.components, for finding one defined twice
  std::map<std::string, SourceLocation> topic_locations_;         // instance.port -> where it was mapped
  std::map<std::string, SourceLocation> unused_input_locations_;  // topic -> where unused_inputs: lists it

  // The rig (docs/dev/architecture.md section 5): parameters a component marks partOfRig() take
  // their value from the scene's rig: block, one value for every component that declares them.
  void readRigNode(const YAML::Node& root);
  void readRigParameter(const ParameterSpec& p, ComponentInstance& instance, Scene& scene);
  void checkRigKeys(const Scene& scene);
  YAML::Node rig_node_;
  std::map<std::string, std::pair<const ParameterSpec*, std::string>> rig_declared_;  // name -> spec, type
};

void SceneValidator::applyOverrides(YAML::Node& root, const std::vector<Override>& overrides) {
  // Overrides are parsed as YAML and grafted into the tree; errors about their values name the
  // command line, not the file.
  for (const auto& o : overrides) {
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      errors_.push_back("--set " + o.text + ": error: " + e.msg);
      continue;
    }
    if (auto structure = yamlStructureErrors(value, "--set " + o.text); !structure.empty()) {
      errors_.insert(errors_.end(), structure.begin(), structure.end());
      continue;
    }
    if (value.IsNull()) value = YAML::Node(std::string());
    override_nodes_.emplace_back(value, o.text);
    override_keys_.emplace_back(o.path.back(), o.text);
    // Top-level keys and clock.* apply directly; anything else is component.parameter.
    static const std::set<std::string> top_level = {"name",         "domain_id",   "seed",    "on_crash",
                                                    "max_restarts", "dds_profile", "security"};
    if (o.path.size() == 1 && top_level.count(o.path[0])) {
      root[o.path[0]] = value;
    } else if (o.path.size() == 2 && o.path[0] == "clock") {
      root["clock"][o.path[1]] = value;
    } else if (o.path.size() == 2 && o.path[0] == "rig") {
      root["rig"][o.path[1]] = value;
    } else if (o.path.size() == 2) {
      YAML::Node components = root["components"];
      if (!components || !components[o.path[0]]) {
        errors_.push_back("--set " + o.text + ": error: the scene has no component '" + o.path[0] + "'");
        continue;
      }
      components[o.path[0]]["params"][o.path[1]] = value;
    } else {
      std::string keys;
      for (const auto& k : top_level) keys += (keys.empty() ? "" : ", ") + k;
      errors_.push_back("--set " + o.text +
                        ": error: expected component.parameter, clock.key, rig.key or a top-level key (" + keys +
                        "); the topic lists are set in the scene file");
    }
  }
}

std::string SceneValidator::resolvePath(const std::string& value, const std::string& directory) const {
  fs::path p(value);
  if (p.is_relative()) p = fs::path(directory) / p;
  return p.lexically_normal().string();
}

Scene SceneValidator::validate(YAML::Node root, const std::vector<Override>& overrides) {
  Scene scene;
  scene.file = file_;
  scene.directory = fs::path(file_).parent_path().string();
  if (!root.IsMap()) {
    error(root, "a scene is a YAML mapping with at least a 'components' key");
    throw SceneError(errors_);
  }
  applyOverrides(root, overrides);
  checkKeys(root,
            {"name", "domain_id", "dds_profile", "security", "seed", "clock", "on_crash", "max_restarts", "rig",
             "external_topics", "outputs_for_tools", "unused_inputs", "components"},
            "the scene");
  readRigNode(root);
  readTopLevel(root, scene);
  if (root["clock"]) readClock(root["clock"], scene);

  const YAML::Node components = root["components"];
  if (!components) {
    error(SourceLocation{file_, 1, 1}, "the scene has no 'components'");
  } else if (!components.IsMap()) {
    error(components, "'components' must map instance names to components");
  } else if (components.size() == 0) {
    // A run of nothing would report negative sim time; say what is wrong instead.
    error(components, "'components' is empty: the scene has nothing to run");
  } else {
    for (const auto& kv : components) readComponent(kv.first, kv.second, scene);
    checkRigKeys(scene);
    const std::size_t errors_before = errors_.size();
    resolvePortReferences(scene, pending_, errors_);
    resolveScenePorts(scene, errors_);
    // A reference that failed leaves its port on its default topic: checking that would only
    // add confusing messages.
    if (errors_.size() == errors_before) checkConnections(scene, topic_locations_, unused_input_locations_, errors_);
  }
  if (root["security"]) readSecurity(root["security"], scene);
  if (scene.clock.mode == ClockMode::kLockstep && scene.on_crash == CrashPolicy::kRestart) {
    error(root["on_crash"],
          "on_crash: restart needs clock.mode realtime: a restarted process cannot rejoin "
          "a deterministic lockstep run");
  }
  if (!errors_.empty()) throw SceneError(errors_);
  return scene;
}

void SceneValidator::readTopLevel(const YAML::Node& root, Scene& scene) {
  scene.name = fs::path(file_).stem().string();
  if (root["name"]) {
    if (auto v = scalar<std::string>(root["name"], "name")) {
      // Printed in every run's first line, graphs and records: a terminal must show it, not obey it.
      const bool printable = std::none_of(v->begin(), v->end(), [](char c) {
        const auto byte = static_cast<unsigned char>(c);
        return byte < 0x20 || byte == 0x7f;
      });
      if (printable)
        scene.name = *v;
      else
        error(root["name"],
              "name '" + *v +
                  "' holds control characters (a newline, an escape, NUL ...); a scene's name is one printable line");
    }
  }
  if (root["domain_id"]) {
    if (auto v = scalar<int>(root["domain_id"], "domain_id")) {
      if (*v < 0 || *v > kMaxDomainId)
        error(root["domain_id"], "domain_id must be between 0 and " + std::to_string(kMaxDomainId));
      else
        scene.domain_id = *v;
    }
  } else {
    // As a ROS 2 user expects: the scene's domain_id (or --set domain_id=N) first, then this.
    try {
      scene.domain_id = rosDomainIdFromEnvironment().value_or(scene.domain_id);
    } catch (const std::invalid_argument& e) {
      errors_.push_back(std::string("error: ") + e.what() + " (the scene names no domain_id, so it is used)");
    }
  }
  if (root["seed"]) {
    if (auto v = scalar<std::uint64_t>(root["seed"], "seed")) scene.seed = *v;
  }
  if (root["max_restarts"]) {
    if (auto v = scalar<int>(root["max_restarts"], "max_restarts")) {
      if (*v < 0)
        error(root["max_restarts"], "max_restarts must be 0 or more");
      else
        scene.max_restarts = *v;
    }
  }
  if (const YAML::Node topics = root["external_topics"])
    readTopicList(topics, "external_topics", scene.external_topics);
  if (const YAML::Node topics = root["outputs_for_tools"]) {
    readTopicList(topics, "outputs_for_tools", scene.outputs_for_tools);
  }
  if (const YAML::Node topics = root["unused_inputs"]) {
    readTopicList(topics, "unused_inputs", scene.unused_inputs);
    if (topics.IsSequence()) {
      for (const auto& item : topics) {
        if (item.IsScalar()) unused_input_locations_.emplace(item.Scalar(), locationOf(item));
      }
    }
  }
  if (root["on_crash"]) {
    if (auto v = scalar<std::string>(root["on_crash"], "on_crash")) {
      if (*v == "stop")
        scene.on_crash = CrashPolicy::kStop;
      else if (*v == "restart")
        scene.on_crash = CrashPolicy::kRestart;
      else
        error(root["on_crash"], "on_crash must be 'stop' or 'restart', not '" + *v + "'");
    }
  }
  if (root["dds_profile"]) {
    if (auto v = scalar<std::string>(root["dds_profile"], "dds_profile")) {
      scene.dds_profile = resolvePath(*v, directoryOf(root["dds_profile"]));
      if (!isRegularFile(scene.dds_profile)) {
        error(root["dds_profile"], "dds_profile: file not found: " + scene.dds_profile);
      }
    }
  }
}

// security: {directory: DIR}, checked once the processes are known: every identity the run
// needs (each process's, the launcher's clock in lockstep) must be there and valid.
void SceneValidator::readSecurity(const YAML::Node& node, Scene& scene) {
  if (!node.IsMap()) {
    error(node, "'security' must be a mapping: security: {directory: DIR} (made by `uampc security init DIR`)");
    return;
  }
  checkKeys(node, {"directory"}, "security");
  if (!node["directory"]) {
    error(node, "security: 'directory' is missing (what `uampc security init DIR --scene SCENE.yaml` made)");
    return;
  }
  const auto directory = scalar<std::string>(node["directory"], "security.directory");
  if (!directory) return;
  scene.security_directory = resolvePath(*directory, directoryOf(node["directory"]));
  if (!check_security_) return;
  if (!isDirectory(scene.security_directory)) {
    error(node["directory"], "security.directory: not a directory: " + scene.security_directory +
                                 " (make it with `uampc security init DIR --scene SCENE.yaml`)");
    return;
  }
  std::vector<std::string> identities = scene.processes();
  if (scene.clock.mode == ClockMode::kLockstep) identities.push_back(kLauncherIdentity);
  std::set<std::string> said;  // the CA and the governance are every identity's: say their problems once
  for (const auto& name : identities) {
    if (!isDirectory(identityFolder(scene.security_directory, name))) {
      error(node["directory"],
            "security: no identity for " +
                (name == kLauncherIdentity ? std::string("the launcher's clock") : "process '" + name + "'") + " (" +
                identityFolder(scene.security_directory, name) +
                "); make the directory again with `uampc security init DIR --scene` this scene");
      continue;
    }
    const DdsIdentity identity = securityIdentity(scene.security_directory, name);
    for (const auto& problem : checkSecurityIdentity(identity)) {
      if (said.insert(problem).second) error(node["directory"], "security: identity '" + name + "': " + problem);
    }
    // Keys open to others are used, with a word (docs/decisions/security-key-permissions.md).
    for (const auto& warning : securityPermissionWarnings(identity)) {
      if (said.insert(warning).second) {
        scene.warnings.push_back(diagnostic(locationOf(node["directory"]), "warning", "security: " + warning));
      }
    }
  }
}

void SceneValidator::readClock(const YAML::Node& node, Scene& scene) {
  if (!node.IsMap()) {
    error(node, "'clock' must be a mapping (mode, step, duration, ack_timeout, real_time_factor, in_process)");
    return;
  }
  checkKeys(node, {"mode", "step", "duration", "ack_timeout", "real_time_factor", "in_process"}, "clock");
  if (node["in_process"]) {
    if (auto v = scalar<bool>(node["in_process"], "clock.in_process")) scene.clock.in_process = *v;
  }
  if (node["mode"]) {
    if (auto v = scalar<std::string>(node["mode"], "clock.mode")) {
      if (*v == "lockstep")
        scene.clock.mode = ClockMode::kLockstep;
      else if (*v == "realtime")
        scene.clock.mode = ClockMode::kRealtime;
      else
        error(node["mode"], "clock.mode must be 'lockstep' or 'realtime', not '" + *v + "'");
    }
  }
  auto positive = [&](const char* key, double lo, double hi, auto assign) {
    if (!node[key]) return;
    if (auto v = scalar<double>(node[key], std::string("clock.") + key)) {
      if (!std::isfinite(*v) || *v < lo || *v > hi) {
        std::ostringstream msg;
        msg << "clock." << key << " must be between " << lo << " and " << hi << ", not " << node[key].Scalar();
        error(node[key], msg.str());
      } else {
        assign(*v);
      }
    }
  };
  positive("step", 1e-6, 1.0, [&](double v) { scene.clock.step = Time::fromSeconds(v); });
  positive("duration", 0.0, 1e7, [&](double v) { scene.clock.duration_s = v; });
  positive("ack_timeout", 0.1, 3600.0, [&](double v) { scene.clock.ack_timeout_s = v; });
  // 0: as fast as the components go. Otherwise at least 0.001: 1e-300 overflowed the pacing (which
  // then stopped pacing) and 1e-12 put the clock to sleep for years, deaf to Ctrl-C.
  positive("real_time_factor", 0.0, 1000.0, [&](double v) {
    if (v > 0.0 && v < kMinRealTimeFactor) {
      error(node["real_time_factor"], "clock.real_time_factor must be 0 (as fast as possible) or at least 0.001, not " +
                                          node["real_time_factor"].Scalar());
    } else {
      scene.clock.real_time_factor = v;
    }
  });
}

void SceneValidator::readComponent(const YAML::Node& key, const YAML::Node& node, Scene& scene) {
  ComponentInstance instance;
  instance.name = key.as<std::string>();
  instance.location = at(key);
  static const std::regex name_pattern("[A-Za-z][A-Za-z0-9_]*");
  if (!std::regex_match(instance.name, name_pattern)) {
    error(key, "component name '" + instance.name + "' must start with a letter and use only letters, digits, _");
    return;
  }
  if (instance.name.size() > kMaxNameLength) {
    error(key, "component name '" + instance.name.substr(0, 20) + "...' is longer than " +
                   std::to_string(kMaxNameLength) + " characters");
    return;
  }
  if (!node.IsMap()) {
    error(node, "component '" + instance.name + "' must be a mapping with at least 'type'");
    return;
  }
  checkKeys(node, {"type", "process", "params", "topics"}, "component '" + instance.name + "'");
  if (!node["type"]) {
    error(key, "component '" + instance.name + "' has no 'type'");
    return;
  }
  auto type = scalar<std::string>(node["type"], "type");
  if (!type) return;
  instance.type = *type;
  try {
    instance.library = catalog_.find(instance.type);
  } catch (const std::exception& e) {
    error(node["type"], e.what());
    return;
  }
  if (!instance.library) {
    const std::string guess = closestMatch(instance.type, catalog_.typeNames());
    std::string searched;
    for (const auto& d : catalog_.directories()) searched += (searched.empty() ? "" : ", ") + d;
    error(node["type"], "unknown component type '" + instance.type + "'" +
                            (guess.empty() ? "" : "; did you mean '" + guess + "'?") + " (searched: " + searched +
                            "; `uampc components` lists what is installed)");
    return;
  }
  if (node["process"]) {
    if (auto v = scalar<std::string>(node["process"], "process")) {
      static const std::regex process_pattern("[a-z][a-z0-9_]*");
      if (!std::regex_match(*v, process_pattern)) {
        error(node["process"], "process name '" + *v + "' must use lower-case letters, digits and _");
      } else if (v->size() > kMaxNameLength) {
        error(node["process"], "process name '" + v->substr(0, 20) + "...' is longer than " +
                                   std::to_string(kMaxNameLength) + " characters");
      } else {
        instance.process = *v;
      }
    }
  }
  const ComponentSpec& spec = instance.library->spec();
  readParameters(node["params"], instance, spec, scene);
  checkRequirements(node["params"], instance, spec);
  std::vector<PortReference> references;
  readTopics(node["topics"], instance, spec, references);
  if (!component_names_.insert(instance.name).second) {
    error(key, "component '" + instance.name + "' is defined twice");
    return;
  }
  for (auto& r : references) {
    r.instance = scene.components.size();
    pending_.push_back(std::move(r));
  }
  scene.components.push_back(std::move(instance));
}

void SceneValidator::readParameters(const YAML::Node& node, ComponentInstance& instance, const ComponentSpec& spec,
                                    Scene& scene) {
  const std::string owner = "component '" + instance.name + "' (" + instance.type + ")";
  if (node && !node.IsMap() && !node.IsNull()) {
    error(node, "'params' of " + owner + " must be a mapping");
    return;
  }
  std::set<std::string> given;
  if (node && node.IsMap()) {
    for (const auto& kv : node) {
      const std::string name = kv.first.as<std::string>();
      given.insert(name);
      const ParameterSpec* p = spec.findParameter(name);
      if (!p) {
        std::vector<std::string> names;
        for (const auto& q : spec.parameters()) names.push_back(q.name);
        const std::string guess = closestMatch(name, names);
        error(kv.first, "unknown parameter '" + name + "' for " + owner +
                            (guess.empty() ? "" : "; did you mean '" + guess + "'?"));
        continue;
      }
      if (p->rig) {
        error(kv.first, "'" + name + "' is part of the rig, shared by every component that uses it: set it once " +
                            "under rig: (or --set rig." + name + "=...), not in the params of " + owner);
        continue;
      }
      if (auto v = readValue(kv.second, *p, owner)) instance.params[name] = *v;
    }
  }
  for (const auto& p : spec.parameters()) {
    if (given.count(p.name)) continue;
    if (p.rig) {
      readRigParameter(p, instance, scene);
    } else if (p.required()) {
      error(instance.location,
            "missing required parameter '" + p.name + "' (" + toString(p.type) + ": " + p.doc + ") for " + owner);
    } else {
      instance.params[p.name] = *p.default_value;
    }
  }
}

void SceneValidator::checkRequirements(const YAML::Node& params, const ComponentInstance& instance,
                                       const ComponentSpec& spec) {
  auto text = [&](const std::string& name) -> std::string {
    const auto value = instance.params.find(name);
    const auto* s = value == instance.params.end() ? nullptr : std::get_if<std::string>(&value->second);
    return s ? *s : std::string();
  };
  for (const auto& r : spec.requirements()) {
    if (text(r.parameter) != r.value) continue;
    const std::string needed = text(r.needed);
    if (r.needed_value.empty() ? !needed.empty() : needed == r.needed_value) continue;
    const YAML::Node where = params && params.IsMap() ? params[r.parameter] : YAML::Node();
    const std::string what = r.needed_value.empty() ? r.needed : r.needed + ": " + r.needed_value;
    error(where ? locationOf(where) : instance.location, r.parameter + ": " + r.value + " needs " + what +
                                                             " (component '" + instance.name + "', " + instance.type +
                                                             ")");
  }
}

void SceneValidator::readRigNode(const YAML::Node& root) {
  const YAML::Node rig = root["rig"];
  if (!rig) return;
  if (!rig.IsMap()) {
    error(rig, "'rig' must map rig parameters to values (rig.tilt_deg, rig.lidar_model, ...)");
    return;
  }
  rig_node_.reset(rig);
}

void SceneValidator::readRigParameter(const ParameterSpec& p, ComponentInstance& instance, Scene& scene) {
  const auto [declared, inserted] = rig_declared_.emplace(p.name, std::make_pair(&p, instance.type));
  const ParameterSpec& first = *declared->second.first;
  if (!inserted && (first.type != p.type || first.default_value != p.default_value)) {
    error(instance.location, "rig parameter '" + p.name + "' is declared differently by component types '" +
                                 declared->second.second + "' and '" + instance.type +
                                 "' (type or default): the installed components disagree on the rig");
    return;
  }
  if (auto known = scene.rig.find(p.name); known != scene.rig.end()) {
    instance.params[p.name] = known->second;
    return;
  }
  const YAML::Node& rig = rig_node_;  // const: a lookup must not add the key
  std::optional<ParameterValue> value = p.default_value;
  if (rig && rig[p.name]) value = readValue(rig[p.name], p, "the rig");
  if (!value) {
    if (!rig || !rig[p.name]) {
      error(instance.location, "missing rig parameter '" + p.name + "' (" + p.doc + "), needed by component '" +
                                   instance.name + "': set it under rig:");
    }
    return;
  }
  scene.rig[p.name] = *value;
  instance.params[p.name] = *value;
}

// A rig key no component of the scene declares is a typo or a leftover: an error, with the
// closest declared name. Two keys that say one fact two ways (ParameterSpec::not_with) are an
// error too: which one would win is not for the reader to guess.
void SceneValidator::checkRigKeys(const Scene& scene) {
  if (!rig_node_) return;
  const YAML::Node& rig = rig_node_;  // const: a lookup must not add the key
  std::vector<std::string> names;
  for (const auto& [name, declared] : rig_declared_) {
    names.push_back(name);
    const std::string& other = declared.first->not_with;
    // An empty list is the parameter's "not set" (a resolved scene writes every rig key, the
    // unset one as []), so it does not count as given.
    const auto given = [&](const std::string& key) {
      return rig[key] && !(rig[key].IsSequence() && rig[key].size() == 0);
    };
    if (!other.empty() && given(name) && given(other)) {
      error(rig[name], "rig." + name + " and rig." + other + " are both given, and both set the same thing (" +
                           declared.first->doc + "): give one");
    }
  }
  for (const auto& kv : rig_node_) {
    const std::string name = kv.first.as<std::string>();
    if (rig_declared_.count(name)) continue;
    const std::string guess = closestMatch(name, names);
    error(kv.first, "no component of scene '" + scene.name + "' uses rig parameter '" + name + "'" +
                        (guess.empty() ? "" : "; did you mean '" + guess + "'?"));
  }
}

std::optional<ParameterValue> SceneValidator::readValue(const YAML::Node& node, const ParameterSpec& spec,
                                                        const std::string& owner) {
  const std::string what = "parameter '" + spec.name + "' of " + owner;
  // `text`: the scalar the number was read from (a list's element, not the list); the message
  // points at `node`, which a --set names.
  auto checkBounds = [&](double v, const std::string& text) {
    if (!std::isfinite(v)) {
      error(node, what + " must be a finite number, not " + text);
      return false;
    }
    if (!spec.withinBounds(v)) {
      error(node, what + " is " + text + ", out of bounds " + spec.boundsText());
      return false;
    }
    return true;
  };
  switch (spec.type) {
    case ParameterType::kBool:
      if (auto v = scalar<bool>(node, what)) return ParameterValue(*v);
      return std::nullopt;
    case ParameterType::kInt:
      if (auto v = scalar<std::int64_t>(node, what)) {
        if (checkBounds(static_cast<double>(*v), node.Scalar())) return ParameterValue(*v);
      }
      return std::nullopt;
    case ParameterType::kDouble:
      if (auto v = scalar<double>(node, what)) {
        if (checkBounds(*v, node.Scalar())) return ParameterValue(*v);
      }
      return std::nullopt;
    case ParameterType::kString:
      if (auto v = scalar<std::string>(node, what)) {
        if (!spec.choices.empty() && std::find(spec.choices.begin(), spec.choices.end(), *v) == spec.choices.end()) {
          std::string allowed;
          for (const auto& c : spec.choices) allowed += (allowed.empty() ? "" : ", ") + c;
          error(node, what + " is '" + *v + "'; allowed: " + allowed);
          return std::nullopt;
        }
        return ParameterValue(*v);
      }
      return std::nullopt;
    case ParameterType::kPath:
      if (auto v = scalar<std::string>(node, what)) {
        if (v->empty()) return ParameterValue(*v);
        const std::string path = resolvePath(*v, directoryOf(node));
        if (!pathExists(path)) {
          error(node, what + ": file not found: " + path);
          return std::nullopt;
        }
        return ParameterValue(path);
      }
      return std::nullopt;
    case ParameterType::kDoubleList: {
      if (!node.IsSequence()) {
        error(node, what + " must be a list of numbers, e.g. [1.0, 2.0]");
        return std::nullopt;
      }
      std::vector<double> values;
      for (const auto& item : node) {
        auto v = scalar<double>(item, what);
        if (!v) return std::nullopt;
        if (!checkBounds(*v, item.Scalar())) return std::nullopt;
        values.push_back(*v);
      }
      const auto* default_list = spec.default_value ? std::get_if<std::vector<double>>(&*spec.default_value) : nullptr;
      const bool none_given = values.empty() && default_list && default_list->empty();
      if (spec.list_length > 0 && values.size() != spec.list_length && !none_given) {
        error(node, what + " must be a list of " + std::to_string(spec.list_length) + " numbers, not " +
                        std::to_string(values.size()));
        return std::nullopt;
      }
      return ParameterValue(values);
    }
    case ParameterType::kStringList: {
      if (!node.IsSequence()) {
        error(node, what + " must be a list of strings, e.g. [/lidar/points, /motor/state]");
        return std::nullopt;
      }
      std::vector<std::string> values;
      for (const auto& item : node) {
        auto v = scalar<std::string>(item, what);
        if (!v) return std::nullopt;
        values.push_back(*v);
      }
      return ParameterValue(values);
    }
  }
  return std::nullopt;
}

// external_topics: [/livox/lidar, ...], outputs_for_tools: [/lidar/points, ...] and
// unused_inputs: [/lidar/imu, ...]: ROS topic names, each once.
void SceneValidator::readTopicList(const YAML::Node& node, const std::string& key, std::vector<std::string>& topics) {
  if (!node.IsSequence()) {
    error(node, key + " must be a list of topics, e.g. [/livox/lidar]");
    return;
  }
  for (const auto& item : node) {
    const auto topic = scalar<std::string>(item, "a topic of " + key);
    if (!topic) continue;
    if (!std::regex_match(*topic, topicPattern()))
      error(item, key + ": '" + *topic + "' is not a ROS topic name (e.g. /livox/lidar)");
    else if (std::find(topics.begin(), topics.end(), *topic) != topics.end())
      error(item, key + ": " + *topic + " is listed twice");
    else
      topics.push_back(*topic);
  }
}

void SceneValidator::readTopics(const YAML::Node& node, ComponentInstance& instance, const ComponentSpec& spec,
                                std::vector<PortReference>& references) {
  instance.ports = spec.ports();
  for (const auto& port : spec.ports()) instance.topics[port.name] = port.default_topic;
  if (!node || node.IsNull()) return;
  if (!node.IsMap()) {
    error(node, "'topics' of component '" + instance.name + "' must map port names to topics");
    return;
  }
  static const std::regex reference_pattern("[A-Za-z][A-Za-z0-9_]*/[A-Za-z_][A-Za-z0-9_]*");
  for (const auto& kv : node) {
    const std::string port = kv.first.as<std::string>();
    const PortSpec* p = spec.findPort(port);
    if (!p) {
      std::vector<std::string> names;
      for (const auto& q : spec.ports()) names.push_back(q.name);
      const std::string guess = closestMatch(port, names);
      error(kv.first, "component '" + instance.name + "' (" + instance.type + ") has no port '" + port + "'" +
                          (guess.empty() ? "" : "; did you mean '" + guess + "'?"));
      continue;
    }
    auto target = scalar<std::string>(kv.second, "topic of port '" + port + "'");
    if (!target) continue;
    topic_locations_[instance.name + "." + port] = at(kv.second);
    if (*target == kClockTopic || target->rfind(kLockstepTopicPrefix, 0) == 0) {
      // The runtime's own topics: a port on them would fight the lockstep clock (a port mapped to
      // /clock crashed the process).
      error(kv.second, "topic " + *target + " is the runtime's own (the lockstep clock); map port '" + port +
                           "' to another topic");
    } else if (std::regex_match(*target, topicPattern())) {
      instance.topics[port] = *target;
    } else if (std::regex_match(*target, reference_pattern)) {
      references.push_back({0, port, *target, locationOf(kv.second)});
    } else {
      error(kv.second, "'" + *target + "' is neither a topic (/name/space) nor a port reference (component/port)");
    }
  }
}

}  // namespace

Scene loadScene(const std::string& path, const std::vector<Override>& overrides, ComponentCatalog& catalog,
                bool check_security) {
  const std::string file = fs::absolute(path).lexically_normal().string();
  if (!isRegularFile(file)) {
    const std::string why = whyNotAFile(file);
    throw SceneError({path + ": error: " + (why == "file not found" ? "scene file not found" : why)});
  }
  const SceneDocument document = SceneDocument::load(file);
  SceneValidator validator(file, document, catalog);
  validator.check_security_ = check_security;
  return validator.validate(document.root, overrides);
}

}  // namespace uampc
