// What one run of an experiment produced: its figures (read back from the evaluator's
// metrics.json), how it went (status, exit code, wall time, real-time factor) and results.json.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"

namespace uampc::app {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

// The paper's figures and a few more, from metrics.json; NaN where the evaluator wrote null (e.g.
// CMPLT of a run shorter than one 5 s window).
struct RunMetrics {
  double ate_m = kMissing;          // the paper's ATE: unaligned RMSE
  double ate_aligned_m = kMissing;  // after Umeyama alignment
  double cmplt = kMissing;          // the paper's CMPLT: voxels per 5 s window, LO's registered scans
  double cmplt_ground_truth = kMissing;
  double rpe_10m_m = kMissing;  // translation RMSE over 10 m segments
  double rpe_100m_m = kMissing;
  double sim_time_s = kMissing;
  double mean_speed = kMissing;  // rad/s
  double distance_m = kMissing;  // the ground truth's path length over the evaluated span
  // Loss of track judged against ground truth: when the estimated speed first strayed more than
  // 1 m/s from the true one (over 1 s); NaN when it never did.
  double runaway_time_s = kMissing;
  long long velocity_resets = 0;  // the LO's (metrics.json lo.velocity_resets): held with some, it recovered
};

// Reads RUN_DIR/metrics.json; nullopt when missing or unreadable (the run did not finish).
std::optional<RunMetrics> readRunMetrics(const std::string& run_directory);

// The launcher's last line: "uampc: X s of sim time in Y s (Zx real time)".
struct LauncherSummary {
  double sim_s = 0.0;
  double wall_s = 0.0;
  double real_time_factor = 0.0;
};
std::optional<LauncherSummary> parseLauncherSummary(const std::string& log_text);

enum class RunStatus {
  kOk,      // ran now and finished
  kReused,  // finished by an earlier invocation (resume)
  kFailed,  // ran now and failed: see run.log
  kNotRun,  // interrupted before it started
};
const char* statusName(RunStatus status);

struct RunResult {
  std::string scene;
  std::string controller;
  std::uint64_t seed = 0;
  std::string directory;  // relative to the experiment's output directory
  RunStatus status = RunStatus::kNotRun;
  int exit_code = -1;
  std::string failure;   // why it failed, for people
  bool retried = false;  // an earlier invocation left it failed or unfinished
  RunMetrics metrics;
  double wall_time_s = kMissing;
  double real_time_factor = kMissing;

  bool finished() const { return status == RunStatus::kOk || status == RunStatus::kReused; }
};

// Fills metrics, wall time and real-time factor of a finished run from its directory.
void readRunOutputs(const std::string& run_directory, RunResult& result);

// results.json: the experiment, its statistics (experiment_statistics.hpp) and every run.
void writeResultsJson(const std::string& path, const Experiment& experiment, const std::vector<RunResult>& results);

}  // namespace uampc::app
