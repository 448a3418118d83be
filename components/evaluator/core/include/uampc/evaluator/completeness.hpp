// Completeness (CMPLT): how many distinct voxels the registered scans hit per time window.
//
// The paper: CMPLT = mean number of 0.5 m voxels scanned per 5 s window. Here:
// - a point p (world frame) lies in voxel floor((p - grid_offset) / voxel_size), an integer triple
//   (computed as floor((p - grid_offset) * (1 / voxel_size)), as OctoMap computes its keys, so
//   both agree on every boundary; the saved OctoMap holds the voxels of the shifted grid);
// - grid_offset shifts the grid's faces off round coordinates: a wall that lies exactly on a voxel
//   face (y = 1.5 m with 0.5 m voxels, as in our axis-aligned indoor worlds and many CAD models)
//   has its points fall on both sides by rounding and counts twice, but only when posed exactly
//   (ground truth); a pose a millimetre off puts them on one side. That made the ground-truth
//   CMPLT of the corridor 1.5 times the registered one while the LO was within 0.2 m;
// - windows are [t0 + k w, t0 + (k + 1) w), t0 the first scan's stamp, w = window_duration; a scan
//   counts in the window of its stamp (header time; a 0.1 s scan is not split);
// - a window's count is the number of distinct voxels hit by its scans;
// - CMPLT is the mean over complete windows: those that end at or before the end time (by default
//   the latest stamp, so the window holding the last scan, which is partial, is reported but not
//   averaged). Windows in which no scan arrived are absent rather than zero: a gap in the data
//   says nothing about what the sensor saw. NaN when no window is complete (a run shorter than w).
// - non-finite points, and points beyond +-2^20 voxels of the origin, are skipped and counted.
// - stamps need not increase: a scan goes to the window of its stamp as long as that window is
//   the latest or the one before it (their voxel sets are kept); a scan older than that, or
//   before t0, adds to the total voxel set only and is counted in late_scans. A non-finite stamp
//   drops the whole scan (invalid_scans).
// The union of all voxels hit is kept too (as keys, the same voxels as OctoMap's leaves), and the
// OctoMap tree is built from it only when saving a .bt file: a flat key set is much cheaper per
// point than octree updates, and nothing reads the tree during the run.
// The evaluator uses two instances: scans posed by the estimate and scans posed by ground truth.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "uampc/evaluator/voxel_key_set.hpp"

namespace uampc::evaluator {

struct CompletenessConfig {
  double voxel_size = 0.5;       // m
  double window_duration = 5.0;  // s
  double grid_offset = 0.0;      // m, on every axis (see above)
};

struct CompletenessWindow {
  long index = 0;      // k
  double start = 0.0;  // s, t0 + k w
  double end = 0.0;    // s, t0 + (k + 1) w
  std::size_t voxels = 0;
  std::size_t scans = 0;
  std::size_t points = 0;  // valid points
  bool complete = false;
};

struct CompletenessReport {
  double mean_voxels_per_window = std::numeric_limits<double>::quiet_NaN();  // CMPLT
  std::size_t complete_windows = 0;
  std::size_t total_voxels = 0;  // distinct voxels over the whole run
  std::size_t scans = 0;
  std::size_t points = 0;               // valid points
  std::size_t invalid_points = 0;       // NaN or inf coordinates
  std::size_t out_of_range_points = 0;  // beyond +-2^20 voxels
  std::size_t late_scans = 0;
  std::size_t invalid_scans = 0;
  std::vector<CompletenessWindow> windows;  // by index
};

class Completeness {
 public:
  explicit Completeness(CompletenessConfig config = {});

  void addScan(double stamp, const std::vector<Eigen::Vector3f>& points_world);

  // Windows ending at or before the latest stamp are complete.
  CompletenessReport report() const;
  // Windows ending at or before end_time (s) are complete, e.g. the run's end.
  CompletenessReport report(double end_time) const;

  std::size_t totalVoxels() const { return total_.size(); }
  // Every voxel hit so far, as integer indices (index * voxel_size is the voxel's lower corner).
  std::vector<Eigen::Vector3i> voxels() const;
  // Writes the voxels hit as occupied leaves of an OctoMap OcTree of resolution voxel_size (.bt,
  // octovis opens it). Returns the number of voxels written: voxels beyond OctoMap's range
  // (+-32768 voxels) are left out. Throws std::runtime_error naming path when it cannot write.
  std::size_t saveOctree(const std::string& path) const;

  const CompletenessConfig& config() const { return config_; }

 private:
  using Key = std::uint64_t;  // 21 bits per axis, offset by 2^20
  using VoxelSet = VoxelKeySet;
  struct OpenWindow {
    long index = 0;
    VoxelSet voxels;
  };
  VoxelSet* openSetFor(long index);

  CompletenessConfig config_;
  double inverse_voxel_size_;
  bool started_ = false;
  double t0_ = 0.0;
  double latest_stamp_ = -std::numeric_limits<double>::infinity();
  std::map<long, CompletenessWindow> windows_;
  OpenWindow current_;   // the latest window
  OpenWindow previous_;  // the one before it (index current_.index - 1), for late scans
  VoxelSet total_;
  std::size_t scans_ = 0;
  std::size_t points_ = 0;
  std::size_t invalid_points_ = 0;
  std::size_t out_of_range_points_ = 0;
  std::size_t late_scans_ = 0;
  std::size_t invalid_scans_ = 0;
};

}  // namespace uampc::evaluator
