// The files of a run directory (`uampc launch --out DIR`), by who writes them. Their contents are
// in time_series.hpp (CSV), metrics_file.hpp (metrics.json), run_info.hpp (run_info.json) and
// run_progress.hpp (progress.json).
#pragma once

#include <optional>
#include <string>

namespace uampc::run_files {

// Written by the evaluator (components/evaluator), metrics.json last, at the end of the run.
inline constexpr char kMetricsFile[] = "metrics.json";
inline constexpr char kEstimateFile[] = "estimate.tum";                  // the LO's poses that were paired
inline constexpr char kGroundTruthFile[] = "ground_truth.tum";           // ground truth at their times
inline constexpr char kAteFile[] = "ate.csv";                            // AteRow
inline constexpr char kCompletenessWindowsFile[] = "cmplt_windows.csv";  // CompletenessWindowRow
inline constexpr char kGroundTruthCompletenessWindowsFile[] = "cmplt_ground_truth_windows.csv";
inline constexpr char kMotorFile[] = "motor.csv";                  // MotorRow, during the run
inline constexpr char kTimingsFile[] = "timings.csv";              // TimingRow, during the run
inline constexpr char kUncertaintyFile[] = "uncertainty.csv";      // UncertaintyRow, during the run
inline constexpr char kScannedVoxelsFile[] = "scanned_voxels.bt";  // OctoMap (evaluator/voxel_octree.hpp)
inline constexpr char kPanoramaDirectory[] = "panorama";           // PNG snapshots, during the run

// "panorama_<sim time, %07.1f>.png": zero-padded, so that names sort by time.
std::string panoramaSnapshotName(double sim_time_s);
// The time part of such a name ("00004.5"), or nullopt for another file.
std::optional<std::string> panoramaSnapshotTime(const std::string& file_name);

// Written by `uampc launch` (runtime launcher.cpp) when the run starts: the resolved
// scene, a scene file that `uampc launch` runs again to reproduce the run, and what the run was
// (run_info.hpp), which the evaluator copies into metrics.json as its "run" object.
inline constexpr char kSceneCopyFile[] = "scene.yaml";
inline constexpr char kRunInfoFile[] = "run_info.json";

// Written by the lockstep clock when the environment names a file (the experiment runner does).
inline constexpr char kProgressFile[] = "progress.json";
inline constexpr char kProgressFileVariable[] = "UAMPC_PROGRESS_FILE";

// Written by the experiment runner (apps/uampc).
inline constexpr char kRunLog[] = "run.log";       // the run's stdout and stderr
inline constexpr char kDoneMarker[] = "done";      // "wall_time_s=<s>": `uampc launch` exited 0
inline constexpr char kFailedMarker[] = "failed";  // why it failed, for people

// path/name
std::string inDirectory(const std::string& directory, const std::string& name);

// The done marker with the wall time the runner measured; throws std::runtime_error naming the
// file when it cannot be written.
void writeDoneMarker(const std::string& run_directory, double wall_time_s);
// Whether the marker exists, and its wall time (NaN when it holds none).
std::optional<double> readDoneMarker(const std::string& run_directory);
void writeFailedMarker(const std::string& run_directory, const std::string& reason);
std::string readFailedMarker(const std::string& run_directory);  // empty when there is none

}  // namespace uampc::run_files
