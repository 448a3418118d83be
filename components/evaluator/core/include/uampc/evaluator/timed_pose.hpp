// A pose at a time, and the ground-truth look-up the evaluator pairs estimates with.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <optional>

namespace uampc::evaluator {

struct TimedPose {
  double time = 0.0;  // s
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

// Ground truth at an arbitrary time, or nothing when it is unknown there (outside the recorded
// trajectory). Poses are associated by exact time: the estimate stamped t is compared with the
// ground truth interpolated at t, never with the nearest recorded pose (the reference code's
// 0.1 s tolerance pairs poses up to 0.1 s apart, an error of 0.1 s times the speed).
using GroundTruthLookup = std::function<std::optional<Eigen::Isometry3d>(double time)>;

}  // namespace uampc::evaluator
