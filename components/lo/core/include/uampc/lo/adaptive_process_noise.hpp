// The constant-velocity model's process noise estimated from what the scans corrected
// (docs/decisions/lo-process-noise-in-point-maps.md).
//
// A fixed velocity random walk density q is either too loose or too tight: at 0.1 (m/s)^2/s and
// (rad/s)^2/s a misleading map turns into velocity and the LO runs away; at 0.001, I2EKF-LO's,
// the slow hand-held paths hold but the fast one (MCD NTU, 10 m/s peaks) cannot be followed
// (docs/results/lo-robustness.md). The density is estimated instead from the innovation, as in
// innovation-based adaptive estimation (Mohamed & Schwarz 1999, J. Geodesy 73: Q^ = (1/N) sum
// dx_j dx_j^T, dx_j the state correction of update j): the velocity corrections of the accepted
// updates over a window. A rig that accelerates leaves the filter's velocity behind by about its
// acceleration times the frame time at every update, so q^ = sum |dv_j|^2 / (3 sum dt_j) (per axis)
// grows to follow it; a steady rig's corrections are noise, and q^ falls to the floor.
#pragma once

#include <deque>

#include "uampc/lo/degeneracy.hpp"

namespace uampc::lo {

struct ProcessNoise {
  double linear = 0.0;   // (m/s)^2/s
  double angular = 0.0;  // (rad/s)^2/s
};

class AdaptiveProcessNoise {
 public:
  // window: s of accepted updates the estimate spans; it is clamped to [floor, ceiling] per part.
  AdaptiveProcessNoise(double window, ProcessNoise floor, ProcessNoise ceiling);

  // An accepted update at time (s) after a frame of dt (s), which changed the predicted velocity by
  // dv (m/s, world) and dw (rad/s, base).
  void add(double time, double dt, const Eigen::Vector3d& dv, const Eigen::Vector3d& dw);
  // The densities for the next prediction: the ceiling until the updates kept span half the
  // window (the start, when the velocity is not known yet), then the estimate within the bounds.
  ProcessNoise estimate() const;

 private:
  struct Correction {
    double time, dt, dv2, dw2;
  };
  double window_;
  ProcessNoise floor_, ceiling_;
  std::deque<Correction> corrections_;
};

}  // namespace uampc::lo
