// How far the estimated speed strays from the true one: a runaway shows here first (the issue of
// an LO whose position has not yet drifted far but whose velocity already has), and an LO can
// run away while still saying it tracks. Velocities are taken over baselines of at least
// `baseline` seconds between paired poses, so that the pose noise of one frame (a centimetre at
// 10 Hz is 0.1 m/s) does not count as a runaway.
#pragma once

#include <optional>
#include <vector>

#include "uampc/evaluator/timed_pose.hpp"

namespace uampc::evaluator {

struct SpeedErrorReport {
  double max = 0.0;                          // m/s, the largest |v_estimated - v_true|
  std::optional<double> first_runaway_time;  // s, when it first exceeded the runaway threshold
};

// estimates[i] and truths[i] are paired (same time), in increasing time.
SpeedErrorReport speedError(const std::vector<TimedPose>& estimates, const std::vector<TimedPose>& truths,
                            double baseline = 1.0, double runaway_threshold = 1.0);

}  // namespace uampc::evaluator
