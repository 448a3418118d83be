// A ground-truth trajectory: timed base poses T_WB, interpolated exactly at any time inside it.
//
// Position is interpolated linearly and attitude by slerp between the two samples around t, so a
// point of a scan gets the pose at its own time, never the pose of the nearest sample.
// Interpolation::kSmooth passes through the same samples with a continuous velocity instead
// (cubic Hermite with Catmull-Rom tangents in position, SQUAD in attitude): with linear/slerp a
// 10 Hz trajectory's velocity and angular velocity jump at every sample, which no rigid body does
// and which a constant-velocity LO cannot follow within a frame.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace uampc::world {

struct TimedPose {
  double time = 0.0;  // s
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // R_WB, unit
};

// What to do with a file's attitude.
enum class AttitudeMode {
  kFromFile,  // the file's attitude, times a fixed frame correction
  kYawOnly,   // only the heading (yaw about world z) of the corrected attitude is kept
  kIdentity,  // attitude dropped, as the reference simulation did
};

// "from_file", "yaw_only" or "identity" (as in scene files); throws std::invalid_argument naming
// the valid values otherwise.
AttitudeMode attitudeModeFromName(const std::string& name);

enum class Interpolation { kLinear, kSmooth };

// "linear" or "smooth"; throws std::invalid_argument otherwise.
Interpolation interpolationFromName(const std::string& name);

class Trajectory {
 public:
  Trajectory() = default;
  // Poses must have strictly increasing times and at least one sample; throws
  // std::invalid_argument otherwise. Orientations are normalised.
  explicit Trajectory(std::vector<TimedPose> poses, Interpolation interpolation = Interpolation::kLinear);

  // T_WB at time t; throws std::out_of_range when t lies outside [startTime(), endTime()].
  Eigen::Isometry3d poseAt(double t) const;
  bool contains(double t) const;

  double startTime() const { return poses_.front().time; }
  double endTime() const { return poses_.back().time; }
  double duration() const { return endTime() - startTime(); }
  bool empty() const { return poses_.empty(); }
  const std::vector<TimedPose>& poses() const { return poses_; }

  Interpolation interpolation() const { return interpolation_; }

  // The same trajectory with every time shifted by offset (s).
  Trajectory shiftedInTime(double offset) const;

 private:
  std::vector<TimedPose> poses_;
  Interpolation interpolation_ = Interpolation::kLinear;
};

// A moving average over `window` seconds of the samples (positions averaged, quaternions summed in
// one hemisphere and normalised; the window shrinks at the ends). Recorded ground truth at 10 Hz
// carries attitude noise (MCD: yaw rate jumping by up to 18 deg/s between samples, roll and pitch
// wobbling) that no vehicle performs; the averaged trajectory is plausible motion, and since the
// simulation plays it and the evaluator compares against it, every controller sees the same one.
Trajectory movingAverage(const Trajectory& trajectory, double window);

// The trajectory preceded by `hold` seconds at its first pose, from which it accelerates evenly into
// its own motion over `ease` seconds (time runs as tau = (t - hold)^2 / (2 ease) there, so the
// speed grows linearly from 0 to the trajectory's); afterwards it is the trajectory, later by
// hold + ease / 2. The eased stretch is resampled every 20 ms. See docs/decisions/start-hold.md.
Trajectory withHeldStart(const Trajectory& trajectory, double hold, double ease);

// Replaces each orientation according to the mode; correction is applied on the right (in the
// body frame): R_WB = R_file * correction. MCD's z-down body frame needs a rotation of pi about x.
void applyAttitudeMode(std::vector<TimedPose>& poses, AttitudeMode mode,
                       const Eigen::Quaterniond& correction);

// Heading-only rotation of a rotation: yaw about world z of its x axis.
Eigen::Quaterniond yawOnly(const Eigen::Quaterniond& q);

}  // namespace uampc::world
