#include "experiment/experiment_file.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <regex>
#include <set>

#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/scene.hpp"
#include "uampc/runtime/yaml_errors.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

std::string joinLines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}

// Collects every problem of the file, so that one invocation reports them all (as scenes do).
class ExperimentValidator {
 public:
  ExperimentValidator(std::string file, const std::map<std::string, std::string>& variables)
      : file_(std::move(file)),
        variables_(variables),
        errors_([this](const YAML::Node& node) { return YamlErrors::locationIn(file_, node); }) {}

  Experiment validate(const YAML::Node& root);

 private:
  void error(const YAML::Node& node, const std::string& message) { errors_.add(node, message); }
  void checkKeys(const YAML::Node& map, const std::set<std::string>& allowed, const std::string& what) {
    errors_.checkKeys(map, allowed, what);
  }
  std::optional<std::string> text(const YAML::Node& node, const std::string& what);
  std::optional<std::string> name(const YAML::Node& node, const std::string& what, std::set<std::string>& seen);
  std::string substitute(const YAML::Node& node, const std::string& value);
  std::vector<std::string> overrides(const YAML::Node& node);
  void readSeeds(const YAML::Node& node, Experiment& experiment);
  void readScenes(const YAML::Node& node, Experiment& experiment);
  void readControllers(const YAML::Node& node, Experiment& experiment);
  void readCompare(const YAML::Node& node, Experiment& experiment);

  std::string file_;
  std::string directory_ = fs::path(file_).parent_path().string();
  const std::map<std::string, std::string>& variables_;
  YamlErrors errors_;
};

std::optional<std::string> ExperimentValidator::text(const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) {
    error(node, what + " must be a single value");
    return std::nullopt;
  }
  return node.Scalar();
}

// Names become directory names under runs/, so they are restricted to characters safe there.
std::optional<std::string> ExperimentValidator::name(const YAML::Node& node, const std::string& what,
                                                     std::set<std::string>& seen) {
  if (!node) return std::nullopt;
  auto value = text(node, what);
  if (!value) return std::nullopt;
  static const std::regex kSafe("[A-Za-z0-9_][A-Za-z0-9_.-]*");
  if (!std::regex_match(*value, kSafe)) {
    error(node, what + " '" + *value + "' may only hold letters, digits, _ . - (it names a directory)");
    return std::nullopt;
  }
  // A directory name has at most 255 bytes (NAME_MAX); the run's directory adds to it.
  constexpr std::size_t kMaxLength = 100;
  if (value->size() > kMaxLength) {
    error(node, what + " '" + value->substr(0, 20) + "...' is longer than " + std::to_string(kMaxLength) +
                    " characters (it names a directory)");
    return std::nullopt;
  }
  if (!seen.insert(*value).second) {
    error(node, what + " '" + *value + "' appears twice");
    return std::nullopt;
  }
  return value;
}

std::string ExperimentValidator::substitute(const YAML::Node& node, const std::string& value) {
  static const std::regex kVariable(R"(\$\{([^}]*)\})");
  std::string out;
  auto begin = std::sregex_iterator(value.begin(), value.end(), kVariable);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    out += value.substr(last, static_cast<std::size_t>(it->position()) - last);
    const std::string variable = (*it)[1];
    const auto found = variables_.find(variable);
    if (found != variables_.end()) {
      out += found->second;
    } else if (variable == "data_dir") {
      error(node, "${data_dir} is used but no --data-dir was given (e.g. --data-dir data/mcd)");
    } else {
      error(node, "unknown variable ${" + variable + "} (known: ${data_dir})");
    }
    last = static_cast<std::size_t>(it->position() + it->length());
  }
  return out + value.substr(last);
}

std::vector<std::string> ExperimentValidator::overrides(const YAML::Node& node) {
  std::vector<std::string> out;
  if (!node) return out;
  if (!node.IsSequence()) {
    error(node, "overrides must be a list of NAME=VALUE texts, e.g. [controller.mode=zero]");
    return out;
  }
  for (const auto& item : node) {
    const auto value = text(item, "an override");
    if (!value) continue;
    const std::string substituted = substitute(item, *value);
    try {
      const Override o = parseOverride(substituted);
      if (o.path.size() == 1 && (o.path[0] == "seed" || o.path[0] == "domain_id")) {
        error(item, o.path[0] + " is set by the experiment (seeds list, one DDS domain per parallel run)");
        continue;
      }
    } catch (const SceneError&) {
      error(item, "'" + *value + "' is not NAME=VALUE (component.parameter=value, clock.key=value or key=value)");
      continue;
    }
    out.push_back(substituted);
  }
  return out;
}

void ExperimentValidator::readSeeds(const YAML::Node& node, Experiment& experiment) {
  if (!node.IsSequence() || node.size() == 0) {
    error(node, "seeds must be a non-empty list of integers, e.g. [1, 2, 3]");
    return;
  }
  experiment.seeds.clear();
  std::set<std::uint64_t> seen;
  for (const auto& item : node) {
    try {
      if (!item.IsScalar() || item.Scalar().empty() || item.Scalar()[0] == '-') throw YAML::Exception({}, "");
      const auto seed = item.as<std::uint64_t>();
      if (!seen.insert(seed).second)
        error(item, "seed " + item.Scalar() + " appears twice");
      else
        experiment.seeds.push_back(seed);
    } catch (const YAML::Exception&) {
      error(item,
            "a seed must be a non-negative integer, not '" + (item.IsScalar() ? item.Scalar() : "a list or map") + "'");
    }
  }
}

void ExperimentValidator::readScenes(const YAML::Node& node, Experiment& experiment) {
  if (!node.IsSequence() || node.size() == 0) {
    error(node, "scenes must be a non-empty list of {name, scene, overrides}");
    return;
  }
  std::set<std::string> seen;
  for (const auto& item : node) {
    if (!item.IsMap()) {
      error(item, "a scene entry is a mapping {name, scene, overrides}");
      continue;
    }
    checkKeys(item, {"name", "scene", "overrides"}, "a scene entry");
    ExperimentScene scene;
    scene.location = YamlErrors::locationIn(file_, item).str();
    if (!item["name"]) error(item, "a scene entry needs a 'name'");
    if (!item["scene"]) error(item, "a scene entry needs a 'scene' file");
    if (auto n = name(item["name"], "scene name", seen)) scene.name = *n;
    if (item["scene"]) {
      if (auto path = text(item["scene"], "scene")) {
        fs::path p(substitute(item["scene"], *path));
        if (p.is_relative()) p = fs::path(directory_) / p;
        scene.scene_file = p.lexically_normal().string();
        if (!isRegularFile(scene.scene_file)) error(item["scene"], "scene file not found: " + scene.scene_file);
      }
    }
    scene.overrides = overrides(item["overrides"]);
    experiment.scenes.push_back(std::move(scene));
  }
}

void ExperimentValidator::readControllers(const YAML::Node& node, Experiment& experiment) {
  if (!node.IsSequence() || node.size() == 0) {
    error(node, "controllers must be a non-empty list of {name, overrides}");
    return;
  }
  experiment.controllers.clear();
  std::set<std::string> seen;
  for (const auto& item : node) {
    if (!item.IsMap()) {
      error(item, "a controller entry is a mapping {name, overrides}");
      continue;
    }
    checkKeys(item, {"name", "overrides"}, "a controller entry");
    ExperimentController controller;
    controller.location = YamlErrors::locationIn(file_, item).str();
    if (!item["name"]) error(item, "a controller entry needs a 'name'");
    if (auto n = name(item["name"], "controller name", seen)) controller.name = *n;
    controller.overrides = overrides(item["overrides"]);
    experiment.controllers.push_back(std::move(controller));
  }
}

void ExperimentValidator::readCompare(const YAML::Node& node, Experiment& experiment) {
  if (!node.IsMap()) {
    error(node, "compare must be a mapping {subject: CONTROLLER, baseline: CONTROLLER}");
    return;
  }
  checkKeys(node, {"subject", "baseline"}, "compare");
  for (auto [key, target] : {std::pair{"subject", &experiment.subject}, std::pair{"baseline", &experiment.baseline}}) {
    if (!node[key]) continue;
    const auto value = text(node[key], std::string("compare.") + key);
    if (!value) continue;
    bool known = false;
    for (const auto& c : experiment.controllers) known = known || c.name == *value;
    if (!known) error(node[key], std::string("compare.") + key + ": no controller named '" + *value + "'");
    *target = *value;
  }
}

Experiment ExperimentValidator::validate(const YAML::Node& root) {
  Experiment experiment;
  experiment.file = file_;
  experiment.name = fs::path(file_).stem().string();
  experiment.controllers = defaultControllers();
  if (!root.IsMap()) {
    error(root, "an experiment is a YAML mapping with at least a 'scenes' list");
    throw ExperimentError(errors_.messages());
  }
  checkKeys(root, {"name", "duration", "seeds", "scenes", "controllers", "compare"}, "the experiment");
  if (root["name"]) {
    if (auto v = text(root["name"], "name")) experiment.name = *v;
  }
  if (const YAML::Node d = root["duration"]) {
    try {
      if (!d.IsScalar()) throw YAML::Exception({}, "");
      experiment.duration_s = d.as<double>();
      if (!(*experiment.duration_s > 0.0)) error(d, "duration must be more than 0 s");
    } catch (const YAML::Exception&) {
      error(d, "duration must be a number of seconds");
    }
  }
  if (root["seeds"]) readSeeds(root["seeds"], experiment);
  if (root["scenes"])
    readScenes(root["scenes"], experiment);
  else
    errors_.add(SourceLocation{file_, 1, 1}, "the experiment has no 'scenes'");
  if (root["controllers"]) readControllers(root["controllers"], experiment);
  if (root["compare"]) readCompare(root["compare"], experiment);
  if (!errors_.empty()) throw ExperimentError(errors_.messages());
  return experiment;
}

}  // namespace

ExperimentError::ExperimentError(std::vector<std::string> messages)
    : std::runtime_error(joinLines(messages)), messages_(std::move(messages)) {}

std::vector<ExperimentController> defaultControllers() {
  return {
      {"ua_mpc", {"controller.mode=ua_mpc"}, "default"},
      {"constant_1.8", {"controller.mode=constant", "controller.constant_speed=1.8"}, "default"},
      {"constant_3.6", {"controller.mode=constant", "controller.constant_speed=3.6"}, "default"},
      {"constant_7.2", {"controller.mode=constant", "controller.constant_speed=7.2"}, "default"},
      {"zero", {"controller.mode=zero"}, "default"},
  };
}

Experiment loadExperiment(const std::string& path, const std::map<std::string, std::string>& variables) {
  const std::string file = fs::absolute(path).lexically_normal().string();
  if (!isRegularFile(file)) throw ExperimentError({path + ": error: experiment file not found"});
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    const std::string where =
        e.mark.is_null() ? file
                         : file + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1);
    throw ExperimentError({where + ": error: " + e.msg});
  }
  if (auto errors = yamlStructureErrors(root, file); !errors.empty()) throw ExperimentError(std::move(errors));
  return ExperimentValidator(file, variables).validate(root);
}

std::vector<std::string> sceneNames(const Experiment& experiment) {
  std::vector<std::string> names;
  for (const auto& s : experiment.scenes) names.push_back(s.name);
  return names;
}

std::vector<std::string> controllerNames(const Experiment& experiment) {
  std::vector<std::string> names;
  for (const auto& c : experiment.controllers) names.push_back(c.name);
  return names;
}

}  // namespace uampc::app
