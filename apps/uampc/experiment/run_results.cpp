#include "experiment/run_results.hpp"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "report/experiment_statistics.hpp"
#include "uampc/run_files/json_text.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/text_file.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

// The paper's RPE figure over one segment length; NaN when the evaluator did not measure it.
double rpeRmse(const run_files::TrajectorySummary& trajectory, double segment_length_m) {
  const run_files::RpeSummary* rpe = trajectory.rpeOver(segment_length_m);
  return rpe ? rpe->translation_m.rmse : kMissing;
}

}  // namespace

std::optional<RunMetrics> readRunMetrics(const std::string& run_directory) {
  const auto file = run_files::readMetricsFile(run_files::inDirectory(run_directory, run_files::kMetricsFile));
  if (!file) return std::nullopt;
  RunMetrics m;
  m.sim_time_s = file->sim_time;
  m.ate_m = file->trajectory.ate.unaligned_m.rmse;
  m.ate_aligned_m = file->trajectory.ate.aligned_m.rmse;
  m.rpe_10m_m = rpeRmse(file->trajectory, 10.0);
  m.rpe_100m_m = rpeRmse(file->trajectory, 100.0);
  m.cmplt = file->cmplt.cmplt;
  m.cmplt_ground_truth = file->cmplt_ground_truth.cmplt;
  m.mean_speed = file->motor.mean_speed;
  m.distance_m = file->trajectory.distance_m;  // NaN from evaluators before it was added
  m.runaway_time_s = file->trajectory.speed_error.first_runaway_time.value_or(kMissing);
  m.velocity_resets = file->lo.velocity_resets;
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
  const fs::path log = run_files::inDirectory(run_directory, run_files::kRunLog);
  if (fs::is_regular_file(log)) {
    if (auto summary = parseLauncherSummary(run_files::readTextFile(log)))
      result.real_time_factor = summary->real_time_factor;
  }
  // The done marker holds the wall time the runner measured (process start to exit).
  if (auto wall = run_files::readDoneMarker(run_directory)) result.wall_time_s = *wall;
}

void writeResultsJson(const std::string& path, const Experiment& experiment, const std::vector<RunResult>& results) {
  run_files::Json json = {{"experiment", experiment.name}, {"file", experiment.file}, {"seeds", experiment.seeds}};
  if (experiment.duration_s) json["duration_s"] = *experiment.duration_s;
  json["subject"] = experiment.subject;
  json["baseline"] = experiment.baseline;
  json["statistics"] = statisticsJson(computeStatistics(experiment, results));
  run_files::Json runs = run_files::Json::array();
  for (const RunResult& r : results) {
    run_files::Json run = {{"scene", r.scene},
                           {"controller", r.controller},
                           {"seed", r.seed},
                           {"status", statusName(r.status)},
                           {"exit_code", r.exit_code},
                           {"retried", r.retried},
                           {"directory", r.directory},
                           {"ate_m", r.metrics.ate_m},
                           {"ate_aligned_m", r.metrics.ate_aligned_m},
                           {"cmplt", r.metrics.cmplt},
                           {"cmplt_ground_truth", r.metrics.cmplt_ground_truth},
                           {"rpe_10m_m", r.metrics.rpe_10m_m},
                           {"rpe_100m_m", r.metrics.rpe_100m_m},
                           {"mean_speed", r.metrics.mean_speed},
                           {"distance_m", r.metrics.distance_m},
                           {"lost_track_at_s", r.metrics.runaway_time_s},
                           {"velocity_resets", r.metrics.velocity_resets},
                           {"sim_time_s", r.metrics.sim_time_s},
                           {"wall_time_s", r.wall_time_s},
                           {"real_time_factor", r.real_time_factor}};
    if (!r.failure.empty()) run["failure"] = r.failure;
    runs.push_back(std::move(run));
  }
  json["runs"] = std::move(runs);
  run_files::writeJsonFile(path, json);
}

}  // namespace uampc::app
