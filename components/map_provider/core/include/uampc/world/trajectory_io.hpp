// Reading and writing ground-truth trajectories.
//
//   MCD CSV: header "num,t,x,y,z,qx,qy,qz,qw", one pose a line (the MCD dataset's ground truth;
//            its quaternions describe a z-down body frame, see TrajectoryReadOptions::forMcd()).
//   TUM:     "t x y z qx qy qz qw", whitespace separated, '#' starts a comment line.
//
// Every error (missing file, wrong column count, a field that is not a finite number, a position
// more than 1e6 m from the origin (coordinate_bound.hpp), a zero quaternion, a time not after the
// previous one, a gap longer than max_gap) throws
// std::runtime_error naming file and line, e.g. "ntu.csv:17: expected 9 columns, got 7".
#pragma once

#include <string>

#include "uampc/world/trajectory.hpp"

namespace uampc::world {

struct TrajectoryReadOptions {
  AttitudeMode attitude = AttitudeMode::kFromFile;
  // Applied in the body frame: R_WB = R_file * frame_correction.
  Eigen::Quaterniond frame_correction = Eigen::Quaterniond::Identity();
  // Largest allowed time between consecutive poses (s); zero or negative disables the check.
  double max_gap = 1.0;
  // Subtract the first pose's time, so the trajectory starts at t = 0 (sim time).
  bool start_at_zero = false;

  // MCD defaults: attitude from the file, turned from its z-down body frame to z-up by a
  // rotation of pi about x.
  static TrajectoryReadOptions forMcd();
};

Trajectory readMcdCsv(const std::string& path, const TrajectoryReadOptions& options = {});
Trajectory readTum(const std::string& path, const TrajectoryReadOptions& options = {});

// By extension: ".csv" is MCD CSV, anything else TUM.
Trajectory readTrajectory(const std::string& path, const TrajectoryReadOptions& options = {});

// Writes TUM format with full precision, whole or absent; throws std::runtime_error "cannot write
// PATH: REASON" if the file cannot be written (run_files::writeTextFile).
void writeTum(const std::string& path, const Trajectory& trajectory);

}  // namespace uampc::world
