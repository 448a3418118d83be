#include "run_results.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "experiment_statistics.hpp"
#include "uampc/evaluator/json_writer.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

// metrics.json is JSON, which yaml-cpp reads; null (NaN in the evaluator) and absent keys give NaN.
double number(const YAML::Node& root, std::initializer_list<const char*> path) {
  std::vector<YAML::Node> chain{root};
  for (const char* key : path) {
    const YAML::Node& current = chain.back();
    if (!current.IsMap() || !current[key]) return kMissing;
    chain.push_back(current[key]);
  }
  const YAML::Node& leaf = chain.back();
  if (!leaf.IsScalar()) return kMissing;
  try {
    return leaf.as<double>();
  } catch (const YAML::Exception&) {
    return kMissing;
  }
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The JSON writer has objects but no lists of objects: a list is written by hand, each element
// indented one level deeper than the writer would put it.
std::string indented(const std::string& text, const std::string& prefix) {
  std::string out;
  for (char c : text) {
    out += c;
    if (c == '\n') out += prefix;
  }
  return out;
}

}  // namespace

std::optional<RunMetrics> readRunMetrics(const std::string& run_directory) {
  const fs::path path = fs::path(run_directory) / "metrics.json";
  if (!fs::is_regular_file(path)) return std::nullopt;
  YAML::Node root;
  try {
    root = YAML::LoadFile(path.string());
  } catch (const YAML::Exception&) {
    return std::nullopt;  // cut short: the evaluator writes it last, a torn file is an unfinished run
  }
  if (!root.IsMap() || !root["sim_time"]) return std::nullopt;
  RunMetrics m;
  m.sim_time_s = number(root, {"sim_time"});
  m.ate_m = number(root, {"trajectory", "ate", "unaligned_m", "rmse"});
  m.ate_aligned_m = number(root, {"trajectory", "ate", "aligned_m", "rmse"});
  m.rpe_10m_m = number(root, {"trajectory", "rpe_10m", "translation_m", "rmse"});
  m.rpe_100m_m = number(root, {"trajectory", "rpe_100m", "translation_m", "rmse"});
  m.cmplt = number(root, {"cmplt", "cmplt"});
  m.cmplt_ground_truth = number(root, {"cmplt_ground_truth", "cmplt"});
  m.mean_speed = number(root, {"motor", "mean_speed"});
  m.distance_m = number(root, {"trajectory", "distance_m"});  // NaN from evaluators before it was added
  m.runaway_time_s = number(root, {"trajectory", "speed_error", "first_runaway_time"});
  return m;
}

std::optional<LauncherSummary> parseLauncherSummary(const std::string& log_text) {
  static const std::regex kLine(
      R"(uampc: ([0-9.eE+-]+) s of sim time in ([0-9.eE+-]+) s \(([0-9.eE+-]+)x real time\))");
  std::optional<LauncherSummary> last;
  for (auto it = std::sregex_iterator(log_text.begin(), log_text.end(), kLine); it != std::sregex_iterator(); ++it) {
    try {
      last = LauncherSummary{std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])};
    } catch (const std::exception&) {
      // not numbers after all: keep the previous line
    }
  }
  return last;
}

const char* statusName(RunStatus status) {
  switch (status) {
    case RunStatus::kOk:
      return "ok";
    case RunStatus::kReused:
      return "reused";
    case RunStatus::kFailed:
      return "failed";
    case RunStatus::kNotRun:
      return "not_run";
  }
  return "unknown";
}

void readRunOutputs(const std::string& run_directory, RunResult& result) {
  if (auto metrics = readRunMetrics(run_directory)) result.metrics = *metrics;
  const fs::path log = fs::path(run_directory) / "run.log";
  if (fs::is_regular_file(log)) {
    if (auto summary = parseLauncherSummary(readText(log))) result.real_time_factor = summary->real_time_factor;
  }
  // The done marker holds the wall time the runner measured (process start to exit).
  const std::string done = readText(fs::path(run_directory) / "done");
  static const std::regex kWall(R"(wall_time_s=([0-9.eE+-]+))");
  std::smatch m;
  if (std::regex_search(done, m, kWall)) result.wall_time_s = std::stod(m[1]);
}

void writeResultsJson(const std::string& path, const Experiment& experiment, const std::vector<RunResult>& results) {
  evaluator::JsonObject head;
  head.set("experiment", experiment.name).set("file", experiment.file);
  std::vector<double> seeds;
  for (auto s : experiment.seeds) seeds.push_back(static_cast<double>(s));
  head.set("seeds", seeds);
  if (experiment.duration_s) head.set("duration_s", *experiment.duration_s);
  head.set("subject", experiment.subject).set("baseline", experiment.baseline);
  head.set("statistics", statisticsJson(computeStatistics(experiment, results)));
  std::string runs;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const RunResult& r = results[i];
    evaluator::JsonObject run;
    run.set("scene", r.scene)
        .set("controller", r.controller)
        .set("seed", r.seed)
        .set("status", statusName(r.status))
        .set("exit_code", r.exit_code)
        .set("retried", r.retried)
        .set("directory", r.directory)
        .set("ate_m", r.metrics.ate_m)
        .set("ate_aligned_m", r.metrics.ate_aligned_m)
        .set("cmplt", r.metrics.cmplt)
        .set("cmplt_ground_truth", r.metrics.cmplt_ground_truth)
        .set("rpe_10m_m", r.metrics.rpe_10m_m)
        .set("rpe_100m_m", r.metrics.rpe_100m_m)
        .set("mean_speed", r.metrics.mean_speed)
        .set("distance_m", r.metrics.distance_m)
        .set("lost_track_at_s", r.metrics.runaway_time_s)
        .set("sim_time_s", r.metrics.sim_time_s)
        .set("wall_time_s", r.wall_time_s)
        .set("real_time_factor", r.real_time_factor);
    if (!r.failure.empty()) run.set("failure", r.failure);
    runs += (i ? ",\n    " : "\n    ") + indented(run.dump(2), "    ");
  }
  std::string text = head.dump(2);
  text.resize(text.size() - 2);  // "\n}": the runs list goes before the closing brace
  text += ",\n  \"runs\": [" + runs + (results.empty() ? "]\n}\n" : "\n  ]\n}\n");
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace uampc::app
