// The U check: does the controller's predicted uncertainty U(theta) rank the motor angles the way
// the LO's registration actually fares at them? (docs/dev/architecture.md section 1, UA-MPC step 3;
// the results: docs/results/u-check.md)
//
// At a probe time t on a world's path:
// 1. The LO runs LiDAR-only from t - warmup to t with the motor at a constant speed, started at
//    the ground truth; its state and local map at t are what a controller would see.
// 2. Predicted: U(theta) at the controller's sample angles (theta_k = k * 5 degrees), computed by
//    the controller itself (UaMpcController::step) from the LO's pose and its local map of the
//    last local_map_window seconds, exactly as the mpc component does.
// 3. Measured, per angle: the next frame is cast with the motor held at theta_k (the static view
//    U describes) from the true trajectory, and registered against the LO's map by the LO's own
//    iterated update from its predicted state:
//    - the trace of the posterior pose covariance (rotation rad^2 + position m^2, the same mix
//      of units as U = trace(Lambda^-1));
//    - the registration error from perturbed starts (Monte Carlo): the predicted pose is moved
//      by Gaussian noise (rotation on the right, as the filter perturbs it; position), the update
//      runs, and its distance from the unperturbed registration is taken (not from ground truth:
//      the map is the LO's, drifted with it); its mean square, rotation^2 (rad^2) + position^2
//      (m^2), over the trials: what is left of a wrong start.
// 4. Spearman's rank correlation of U with each measured figure over the angles (app::spearman).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/mpc/ua_mpc_controller.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::tools {

struct UncertaintyCheckConfig {
  double motor_speed = 3.6;  // rad/s while the LO builds its map before the probe
  double warmup = 20.0;      // s of LO before the probe time
  int trials = 10;           // perturbed starts per angle
  double start_rotation_sigma = 0.5 * 3.14159265358979323846 / 180.0;  // rad, per axis
  double start_position_sigma = 0.1;                                   // m, per axis
  double local_map_window = 5.0;                                       // s, as the lo component publishes its local map
  std::uint64_t seed = 1;                                              // of the perturbations
  lo::OdometryConfig odometry;                                         // LiDAR-only, defaults as the lo component's
  mpc::UaMpcController::Config controller;                             // mode is forced to ua_mpc
};

struct AngleCheck {
  double theta = 0.0;      // rad, motor angle
  double predicted = 0.0;  // U(theta)
  // The same criterion, trace(Lambda^-1) with U's eigenvalue floor, of the information the LO's
  // update actually used (its scan points on its map planes): what U would be if it predicted
  // the correspondences perfectly. Separates the criterion from the prediction of the view.
  double oracle = 0.0;
  double posterior_trace = 0.0;     // trace of the posterior pose covariance, rad^2 + m^2
  double mean_square_error = 0.0;   // from the unperturbed registration, rad^2 + m^2, over the trials
  double rms_rotation = 0.0;        // rad
  double rms_position = 0.0;        // m
  std::size_t correspondences = 0;  // of the unperturbed update
};

struct ProbeResult {
  double time = 0.0;               // s, scan end of the LO's last frame before the probe
  double lo_position_error = 0.0;  // m, the LO's own error at that time
  double lo_rotation_error = 0.0;  // rad
  // The LO had lost track (its own criterion) or its rotation error exceeds 5 degrees: its map is
  // then mangled and the probe measures nothing useful. A position error alone does not count:
  // along a plain corridor the LO drifts tens of metres with a map consistent with itself.
  bool lo_lost = false;
  std::size_t local_map_points = 0;
  std::vector<AngleCheck> angles;
  double spearman_trace = 0.0;         // Spearman(U, posterior trace); NaN if either is constant
  double spearman_error = 0.0;         // Spearman(U, mean square error)
  double spearman_oracle_trace = 0.0;  // Spearman(oracle, posterior trace)
  double spearman_oracle_error = 0.0;  // Spearman(oracle, mean square error)
};

class UncertaintyCheck {
 public:
  // Throws std::invalid_argument on a non-positive warmup, trials < 1 or negative sigmas.
  UncertaintyCheck(const world::World& world, const UncertaintyCheckConfig& config);

  // Throws std::invalid_argument when t leaves no whole frame of warm-up or lies past the path.
  ProbeResult probe(double t);

 private:
  const world::World& world_;
  UncertaintyCheckConfig config_;
  raycaster::RayCaster caster_;
};

}  // namespace uampc::tools
