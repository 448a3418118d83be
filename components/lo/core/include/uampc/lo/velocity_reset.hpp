// What the LO does when it stops trusting its velocity (docs/decisions/lo-velocity-reset.md).
//
// The filter's velocity is what a runaway integrates: in misleading geometry one accepted update
// can give the state a wrong rate (MCD KTH in a 0.4 m point map: 0.4 -> 1.3 rad/s in one frame),
// after which every later scan disagrees with the prediction, is rejected as implausible, and the
// pose coasts on the wrong rate until the loss of track lets any update in. The accepted poses are
// what the map agreed with: their mean motion over the last second is the velocity to go on with.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <optional>

#include "uampc/lo/degeneracy.hpp"
#include "uampc/lo/iterated_ekf.hpp"

namespace uampc::lo {

struct Motion {
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // m/s, world frame
  Eigen::Vector3d w_B = Eigen::Vector3d::Zero();  // rad/s, base frame
};

// The base poses of the frames whose registration was accepted, over a bounded time.
class AcceptedPoses {
 public:
  explicit AcceptedPoses(double window) : window_(window) {}

  // A frame's pose at its end time. Kept: the poses within the window before the newest, and the
  // newest one at or before the window's start.
  void add(double time, const BaseState& state);
  // The mean motion from the oldest pose kept to the newest: none with fewer than two poses, or
  // when they lie less than 10 ms apart.
  std::optional<Motion> meanMotion() const;
  void clear() { poses_.clear(); }

 private:
  struct Stamped {
    double time;
    Eigen::Matrix3d R_WB;
    Eigen::Vector3d r_WB;
  };
  double window_;  // s
  std::deque<Stamped> poses_;
};

// The filter with its velocity replaced by motion: the velocity's correlations with the pose
// dropped (the new velocity does not come from the old pose's errors); its variance set to
// variance, or kept as it was when none is given.
IteratedEkf withVelocity(const IteratedEkf& filter, const Motion& motion, std::optional<double> variance);

// Whether the state moves faster than any rig: a registration that says so is a wrong one.
bool beyondSpeedLimits(const BaseState& state, double max_speed, double max_angular_speed);

}  // namespace uampc::lo
