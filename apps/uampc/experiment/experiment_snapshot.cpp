#include "experiment/experiment_snapshot.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "experiment/plan_directories.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/runtime/file_checks.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace uampc::app {

namespace {

// 2: every run's scene end (end_s, step_s), which what counts as done needs (run_completion.hpp).
constexpr int kSnapshotVersion = 2;

json toJson(const Experiment& e) {
  json scenes = json::array(), controllers = json::array();
  for (const auto& s : e.scenes) {
    scenes.push_back({{"name", s.name}, {"scene", s.scene_file}, {"overrides", s.overrides}, {"location", s.location}});
  }
  for (const auto& c : e.controllers) {
    controllers.push_back({{"name", c.name}, {"overrides", c.overrides}, {"location", c.location}});
  }
  json j = {{"file", e.file},       {"name", e.name},         {"seeds", e.seeds},
            {"scenes", scenes},     {"controllers", controllers}, {"subject", e.subject},
            {"baseline", e.baseline}, {"duration", nullptr}};
  if (e.duration_s) j["duration"] = *e.duration_s;
  return j;
}

json toJson(const PlannedRun& r) {
  return {{"scene", r.scene}, {"controller", r.controller}, {"seed", r.seed},        {"directory", r.directory},
          {"args", r.args},   {"end_s", r.end.duration_s},  {"step_s", r.end.step_s}};
}

Experiment experimentFrom(const json& j) {
  Experiment e;
  e.file = j.at("file").get<std::string>();
  e.name = j.at("name").get<std::string>();
  e.seeds = j.at("seeds").get<std::vector<std::uint64_t>>();
  for (const auto& s : j.at("scenes")) {
    e.scenes.push_back({s.at("name").get<std::string>(), s.at("scene").get<std::string>(),
                        s.at("overrides").get<std::vector<std::string>>(), s.at("location").get<std::string>()});
  }
  for (const auto& c : j.at("controllers")) {
    e.controllers.push_back({c.at("name").get<std::string>(), c.at("overrides").get<std::vector<std::string>>(),
                             c.at("location").get<std::string>()});
  }
  e.subject = j.at("subject").get<std::string>();
  e.baseline = j.at("baseline").get<std::string>();
  if (!j.at("duration").is_null()) e.duration_s = j.at("duration").get<double>();
  return e;
}

// What planRuns writes, and nothing else: the runner adds --out and domain_id itself, so a plan
// must not give an --out (or --overwrite) of its own.
bool isLaunchOfScene(const std::vector<std::string>& args) {
  if (args.size() < 2 || args[0] != "launch" || args[1].empty() || args[1][0] == '-' || args.size() % 2 != 0) {
    return false;
  }
  for (std::size_t i = 2; i < args.size(); i += 2) {
    if (args[i] != "--set") return false;
  }
  return true;
}

PlannedRun runFrom(const json& j, const Experiment& e) {
  PlannedRun r;
  r.scene = j.at("scene").get<std::size_t>();
  r.controller = j.at("controller").get<std::size_t>();
  r.seed = j.at("seed").get<std::uint64_t>();
  r.directory = j.at("directory").get<std::string>();
  r.args = j.at("args").get<std::vector<std::string>>();
  r.end = {j.at("end_s").get<double>(), j.at("step_s").get<double>()};
  if (r.scene >= e.scenes.size() || r.controller >= e.controllers.size()) {
    throw std::out_of_range("run " + r.directory + " names a scene or controller the experiment does not have");
  }
  if (!isLaunchOfScene(r.args)) {
    throw std::out_of_range("run " + r.directory + ": its arguments are not `launch SCENE [--set NAME=VALUE ...]`");
  }
  return r;
}

}  // namespace

void writeExperimentSnapshot(const std::string& output_directory, const ExperimentSnapshot& snapshot) {
  json plan = json::array();
  for (const auto& run : snapshot.plan) plan.push_back(toJson(run));
  const json j = {{"version", kSnapshotVersion}, {"experiment", toJson(snapshot.experiment)}, {"plan", plan}};
  // Whole or not at all, the file and the reason named on failure (text_file.hpp).
  run_files::writeTextFile((fs::path(output_directory) / kExperimentSnapshotFile).string(), j.dump(2) + "\n");
}

ExperimentSnapshot readExperimentSnapshot(const std::string& output_directory) {
  const std::string path = (fs::path(output_directory) / kExperimentSnapshotFile).string();
  if (!isRegularFile(path)) {
    throw ExperimentError({path + ": error: no such file (is " + output_directory +
                           " the --out directory of a `uampc experiment`?)"});
  }
  try {
    const json j = json::parse(run_files::readTextFile(path));
    if (j.at("version").get<int>() != kSnapshotVersion) {
      throw ExperimentError({path + ": error: version " + j.at("version").dump() + ", this uampc reads version " +
                             std::to_string(kSnapshotVersion) +
                             " (plan it again: `uampc experiment EXPERIMENT.yaml --out " + output_directory +
                             " --plan-only` keeps the runs)"});
    }
    ExperimentSnapshot snapshot;
    snapshot.experiment = experimentFrom(j.at("experiment"));
    for (const auto& run : j.at("plan")) snapshot.plan.push_back(runFrom(run, snapshot.experiment));
    if (const std::string problem = planDirectoriesProblem(output_directory, snapshot.plan); !problem.empty()) {
      throw ExperimentError({path + ": error: " + problem + "; nothing was done"});
    }
    return snapshot;
  } catch (const json::exception& e) {
    throw ExperimentError({path + ": error: " + e.what()});
  } catch (const std::out_of_range& e) {
    throw ExperimentError({path + ": error: " + e.what()});
  }
}

}  // namespace uampc::app
