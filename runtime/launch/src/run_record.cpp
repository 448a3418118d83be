#include "uampc/runtime/run_record.hpp"

#include <yaml-cpp/yaml.h>

#include <ctime>
#include <stdexcept>
#include <type_traits>

#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_info.hpp"
#include "uampc/run_files/text_file.hpp"

namespace uampc {

namespace {

const char* const kSceneCopyHeader =
    "# The resolved scene of a run, written by `uampc launch --out` when the run started: every value\n"
    "# after extends:, --set and the defaults. `uampc launch` of this file runs the same scene again\n"
    "# (its paths are absolute); the run's run_info.json says which scene and overrides it came from.\n";

// Numbers as the scene loader reads them back exactly: doubles in their shortest round-trip text
// (yaml-cpp would print 17 digits), integers and booleans as such, strings quoted where YAML needs it.
void emitValue(YAML::Emitter& out, const ParameterValue& value) {
  std::visit(
      [&out](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) {
          out << v;
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          out << std::to_string(v);
        } else if constexpr (std::is_same_v<T, double>) {
          out << formatNumber(v);
        } else if constexpr (std::is_same_v<T, std::string>) {
          out << YAML::DoubleQuoted << v;
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          out << YAML::Flow << YAML::BeginSeq;
          for (double d : v) out << formatNumber(d);
          out << YAML::EndSeq;
        } else {
          out << YAML::Flow << YAML::BeginSeq;
          for (const std::string& s : v) out << YAML::DoubleQuoted << s;
          out << YAML::EndSeq;
        }
      },
      value);
}

void emitClock(YAML::Emitter& out, const ClockSettings& clock) {
  out << YAML::Key << "clock" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "mode" << YAML::Value << (clock.mode == ClockMode::kLockstep ? "lockstep" : "realtime");
  // Divided, not multiplied by 1e-9: 5'000'000 ns prints as 0.005.
  out << YAML::Key << "step" << YAML::Value << formatNumber(static_cast<double>(clock.step.ns) / 1e9);
  out << YAML::Key << "duration" << YAML::Value << formatNumber(clock.duration_s);
  out << YAML::Key << "ack_timeout" << YAML::Value << formatNumber(clock.ack_timeout_s);
  out << YAML::Key << "real_time_factor" << YAML::Value << formatNumber(clock.real_time_factor);
  out << YAML::Key << "in_process" << YAML::Value << clock.in_process;
  out << YAML::EndMap;
}

void emitComponent(YAML::Emitter& out, const ComponentInstance& c) {
  const ComponentSpec& spec = c.library->spec();
  out << YAML::Key << c.name << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "type" << YAML::Value << c.type;
  out << YAML::Key << "process" << YAML::Value << c.process;
  out << YAML::Key << "params" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, value] : c.params) {
    const ParameterSpec* p = spec.findParameter(name);
    if (p && p->rig) continue;  // under rig:, where the loader wants it
    out << YAML::Key << name << YAML::Value;
    emitValue(out, value);
  }
  out << YAML::EndMap;
  bool remapped = false;
  for (const PortSpec& port : spec.ports()) {  // the declared ones: the scene's follow from params
    const std::string& topic = c.topics.at(port.name);
    if (topic == port.default_topic) continue;
    if (!remapped) out << YAML::Key << "topics" << YAML::Value << YAML::BeginMap;
    remapped = true;
    out << YAML::Key << port.name << YAML::Value << topic;
  }
  if (remapped) out << YAML::EndMap;
  out << YAML::EndMap;
}

run_files::Json toJson(const ParameterValue& value) {
  return std::visit([](const auto& v) { return run_files::Json(v); }, value);
}

run_files::Json componentsJson(const Scene& scene) {
  run_files::Json components = run_files::Json::object();
  for (const ComponentInstance& c : scene.components) {
    run_files::Json params = run_files::Json::object();
    for (const auto& [name, value] : c.params) params[name] = toJson(value);
    components[c.name] = {{"type", c.type}, {"process", c.process}, {"params", std::move(params)}};
  }
  return components;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace

std::string resolvedSceneYaml(const Scene& scene) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << scene.name;
  out << YAML::Key << "domain_id" << YAML::Value << scene.domain_id;
  out << YAML::Key << "seed" << YAML::Value << scene.seed;
  if (!scene.dds_profile.empty()) out << YAML::Key << "dds_profile" << YAML::Value << scene.dds_profile;
  if (!scene.security_directory.empty()) {
    out << YAML::Key << "security" << YAML::Value << YAML::BeginMap << YAML::Key << "directory" << YAML::Value
        << scene.security_directory << YAML::EndMap;
  }
  out << YAML::Key << "on_crash" << YAML::Value << (scene.on_crash == CrashPolicy::kRestart ? "restart" : "stop");
  out << YAML::Key << "max_restarts" << YAML::Value << scene.max_restarts;
  if (!scene.external_topics.empty())
    out << YAML::Key << "external_topics" << YAML::Value << YAML::Flow << scene.external_topics;
  if (!scene.outputs_for_tools.empty())
    out << YAML::Key << "outputs_for_tools" << YAML::Value << YAML::Flow << scene.outputs_for_tools;
  if (!scene.unused_inputs.empty())
    out << YAML::Key << "unused_inputs" << YAML::Value << YAML::Flow << scene.unused_inputs;
  emitClock(out, scene.clock);
  if (!scene.rig.empty()) {
    out << YAML::Key << "rig" << YAML::Value << YAML::BeginMap;
    for (const auto& [name, value] : scene.rig) {
      out << YAML::Key << name << YAML::Value;
      emitValue(out, value);
    }
    out << YAML::EndMap;
  }
  out << YAML::Key << "components" << YAML::Value << YAML::BeginMap;
  for (const ComponentInstance& c : scene.components) emitComponent(out, c);
  out << YAML::EndMap << YAML::EndMap;
  if (!out.good()) throw std::logic_error("resolved scene: YAML emitter error: " + out.GetLastError());
  return kSceneCopyHeader + std::string(out.c_str()) + "\n";
}

void writeRunRecord(const Scene& scene, const LaunchOptions& options) {
  const std::string& directory = options.output_directory;
  const std::string copy = run_files::inDirectory(directory, run_files::kSceneCopyFile);
  run_files::writeTextFile(copy, resolvedSceneYaml(scene));  // whole or absent, the reason named

  run_files::RunInfo info;
  info.scene_copy = run_files::kSceneCopyFile;
  info.scene_source = scene.file;
  for (const Override& o : options.overrides) info.overrides.push_back(o.text);
  info.started_utc = utcNow();
  info.seed = scene.seed;
  info.domain_id = scene.domain_id;
  info.duration_s = scene.clock.duration_s;
  info.uampc_version = options.uampc_version;
  info.fastdds_version = options.fastdds_version;
  info.components = componentsJson(scene);
  run_files::writeRunInfoFile(run_files::inDirectory(directory, run_files::kRunInfoFile), info);
}

}  // namespace uampc
