// metrics.json, the evaluator's figures of a run: the document as plain structs. Its keys are
// named once, in metrics_file.cpp, for writing and reading alike; a key missing from the file
// (an older evaluator's) reads as NaN, 0 or nothing.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "uampc/run_files/run_info.hpp"

namespace uampc::run_files {

constexpr double kNotANumber = std::numeric_limits<double>::quiet_NaN();

// Written as null when NaN (JSON has no NaN): e.g. the RMSE of no pairs.
struct ErrorSummary {
  std::uint64_t count = 0;
  double rmse = kNotANumber;
  double mean = kNotANumber;
  double median = kNotANumber;
  double max = kNotANumber;
};

struct AteSummary {
  ErrorSummary unaligned_m;  // the paper's ATE is its rmse
  ErrorSummary aligned_m;    // after the Umeyama alignment
};

// Key "rpe_<length>m", the length printed shortest (rpe_10m).
struct RpeSummary {
  double segment_length_m = kNotANumber;
  ErrorSummary translation_m;
  ErrorSummary translation_percent;
  ErrorSummary rotation_deg;
};

struct SpeedErrorSummary {
  double max_m_s = kNotANumber;
  // When the estimated speed first strayed more than 1 m/s from the true one over 1 s (the run
  // lost track); absent when it never did.
  std::optional<double> first_runaway_time;
};

struct TrajectorySummary {
  std::uint64_t estimates = 0, paired = 0, unpaired = 0, invalid = 0;
  double distance_m = kNotANumber;  // the ground truth's path length over the evaluated span
  AteSummary ate;
  std::vector<RpeSummary> rpe;  // in the evaluator's order of segment lengths
  SpeedErrorSummary speed_error;

  const RpeSummary* rpeOver(double segment_length_m) const;  // nullptr when not evaluated
};

struct CompletenessSummary {
  double cmplt = kNotANumber;  // the paper's CMPLT: mean voxels per complete window
  std::uint64_t complete_windows = 0, windows = 0, total_voxels = 0, scans = 0, points = 0;
  std::uint64_t invalid_points = 0, out_of_range_points = 0, late_scans = 0, invalid_scans = 0;
};

// Per 0.1 s control period where it says "change".
struct MotorSummary {
  double mean_speed = kNotANumber;  // rad/s
  double speed_std = kNotANumber;
  double command_change_rms = kNotANumber;
  double speed_change_rms = kNotANumber;
};

// The LO's own account of its losses of track.
struct LoSummary {
  std::optional<double> first_lost_time;  // s; absent: never lost
  std::int64_t lost_frames = 0;
  std::int64_t rejected_updates = 0;
  // Times the LO reset its velocity after a rejected update or at a loss (its velocity_resets on
  // /lo/metrics): a run that held with resets recovered, one without held outright.
  std::int64_t velocity_resets = 0;
  std::int64_t frames = 0;             // frames the LO reported on (/lo/metrics)
  std::int64_t degenerate_frames = 0;  // of them, with a degenerate pose direction
};

struct MetricsDocument {
  double sim_time = kNotANumber;  // s
  // The scene's clock.duration, s, from the run record; absent when the run is open-ended or was
  // not started by `uampc launch --out`.
  std::optional<double> scene_duration;
  // Whether sim_time reached scene_duration: false for a run cut short (a stop signal, a failed
  // process), which no experiment counts as done; absent with scene_duration.
  std::optional<bool> reached_end;
  TrajectorySummary trajectory;
  CompletenessSummary cmplt;               // from the LO's registered scans
  CompletenessSummary cmplt_ground_truth;  // from the raw scans placed with ground truth
  MotorSummary motor;
  LoSummary lo;
  // What the run was (run_info.hpp): absent when the run was not started by `uampc launch --out`
  // (e.g. `uampc run-process` by hand) or was made before metrics.json recorded it. Read back
  // only when whole: a torn or older "run" object reads as absent.
  std::optional<RunInfo> run;
};

// Throws std::runtime_error naming path on failure.
void writeMetricsFile(const std::string& path, const MetricsDocument& metrics);
// nullopt when the file is missing, torn or not a metrics document (no sim_time): a run that did
// not finish (the evaluator writes it last).
std::optional<MetricsDocument> readMetricsFile(const std::string& path);

}  // namespace uampc::run_files
