// Ground truth between recorded poses: linear in position, slerp in attitude.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <vector>

#include "uampc/evaluator/timed_pose.hpp"

namespace uampc::evaluator {

// The pose at time between a.time and b.time (a.time < b.time): position linear, attitude slerp.
Eigen::Isometry3d interpolatePose(const TimedPose& a, const TimedPose& b, double time);

// A trajectory kept sorted by time, interpolated at any time inside [startTime(), endTime()].
// Usable as a GroundTruthLookup (wrap it in a lambda that holds a reference, or copy it).
class PoseInterpolator {
 public:
  PoseInterpolator() = default;
  // Poses in any order: they are sorted by time. A pose with a non-finite time or a time already
  // present is dropped (the first one stays) and counted in droppedPoses().
  explicit PoseInterpolator(std::vector<TimedPose> poses);

  // Adds one pose (streamed ground truth); appending in increasing time is O(1), an older pose is
  // inserted at its place. Returns false (and counts it) when it is dropped as above.
  bool add(const TimedPose& pose);

  // Forgets the poses no lookup at `time` or later needs (all before the last pose at or before
  // `time`), so that streamed ground truth over a long run stays a bounded window. Erases only
  // when at least `batch` poses can go, so that the cost per pose stays constant.
  void dropBefore(double time, std::size_t batch = 4096);

  // The pose at time, or nothing outside [startTime(), endTime()] (no extrapolation).
  std::optional<Eigen::Isometry3d> operator()(double time) const;

  bool empty() const { return poses_.empty(); }
  std::size_t size() const { return poses_.size(); }
  double startTime() const { return poses_.front().time; }  // only when !empty()
  double endTime() const { return poses_.back().time; }     // only when !empty()
  std::size_t droppedPoses() const { return dropped_; }
  const std::vector<TimedPose>& poses() const { return poses_; }

 private:
  std::vector<TimedPose> poses_;
  std::size_t dropped_ = 0;
};

}  // namespace uampc::evaluator
