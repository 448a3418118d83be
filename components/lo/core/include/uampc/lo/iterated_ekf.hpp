// Iterated EKF on the constant-velocity state of the base, with point-to-plane measurements.
//
// State x = (R_WB, r_WB, v_W, w_B); error state (12) = [dtheta, dr, dv, dw], with the rotation
// perturbed on the right: R = R_hat Exp(dtheta). Units: rad, m, m/s, rad/s.
//
// Prediction (constant velocity over dt):
//   R- = R Exp(w dt),  r- = r + v dt,  v- = v,  w- = w            (state prediction x- = f(x))
//   P- = F P F^T + Q                                               (covariance prediction)
// where q is the spectral density of a velocity random walk, integrated over dt:
//   Q = q [dt^3/3  dt^2/2; dt^2/2  dt] on each (pose, velocity) pair: (dtheta, dw) with the
// angular q, (dr, dv) with the linear q.
//
// Update: residual of a point i (base frame p_i at time offset tau_i) against its map plane
//   z_i = n^T ( R Exp(w tau_i) p_i + r + v tau_i ) + d              (measurement model h(x))
// so the deskew is part of the measurement and v, w are observed inside one frame too.
// The iterated update (Bell & Cathey 1993) is Gauss-Newton on the MAP cost
//   ||x (-) x-||^2_{P-^-1} + sum_i z_i^2 / sigma^2,
// re-linearised at every iterate x_j (planes re-associated when x_j has moved far enough):
//   (P-^-1 + H^T H / sigma^2) dx = -H^T z / sigma^2 - P-^-1 (x_j (-) x-),  x_{j+1} = x_j (+) dx
// which is the IEKF step  x_{j+1} = x- (+) K_j ( -z_j + H_j (x_j (-) x-) ),
//   K_j = P- H_j^T (H_j P- H_j^T + sigma^2 I)^-1,
// written in information form: only 12x12 matrices, however many points there are. The Jacobian
// of x_j (-) x- in the rotation is taken as identity, as FAST-LIO and I2EKF-LO do.
// The posterior covariance is P+ = (I - K H) P- = (P-^-1 + H^T H / sigma^2)^-1.
//
// The frame's own velocity (UpdateOptions::frame_velocity_std_*: off here, the odometry's config
// turns it on). The model above
// makes each frame's deskew velocity the filter's velocity, so what a frame says of its velocity
// from its points' times goes into the state at full weight. That view is the weakest part of a
// scan, and its errors are not independent per point: a wall seen at one instant of the frame
// carries its 2 cm of map error into every point on it, which reads as 0.4 m/s
// (docs/results/lo-degenerate-geometry.md, "Each frame's own velocity"). With the option, the
// frame's deskew velocity is the state's plus a deviation e = (dv_W, dw_B), about the frame's
// middle tau_mid (FrameDeviation), with a prior e ~ N(0, diag(std^2)):
//   z_i = n^T ( R Exp(w tau_mid) Exp((w + dw)(tau_i - tau_mid)) p_i + r + v tau_i
//              + dv (tau_i - tau_mid) ) + d
// The iterated update then solves for the 18 unknowns (dx, e) and keeps the 12 of the state, with
// the information of e marginalised out (Schur complement). A frame whose points say its velocity
// differs, in a fast turn, still deskews itself with what they say; the state learns from that at
// most one std per frame, and otherwise from how the pose at the frame's middle moves from frame
// to frame (the frame's middle keeps that pose out of the deviation's reach).
//
// Outliers: the iterations first converge with every correspondence, then a residual gate
// (3 robust standard deviations, at least min_residual_gate) drops wrong planes and the
// iterations converge again. Gating from the start would drop the inliers of whatever direction
// the prediction got wrong; not gating at all leaves a few wrong planes (points on surfaces the
// map has not seen yet, edges) that bias a noise-free registration by several millimetres.
//
// Seen side: a plane is matched only if the sensor sees it from the side its map points were
// seen from. A floor slab or a wall is two faces 0.2-0.3 m apart, well inside the neighbour
// search; a sensor that has only seen a slab's underside and rises above it (a stairwell) sees
// the whole floor at once, and every floor point would find the underside's plane 0.3 m below
// it. Those thousands of consistent wrong matches turned the pose by 14 degrees in one frame on
// the multilevel world; the residual gate cannot catch them, as they are the majority.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "uampc/lo/degeneracy.hpp"
#include "uampc/lo/deskew.hpp"
#include "uampc/lo/inertial.hpp"
#include "uampc/lo/local_map.hpp"
#include "uampc/lo/scan.hpp"

namespace uampc::lo {

// Which correspondences the update keeps. kResidual (ours): every one until the iterations
// converge, then those within the residual gate below. kRangeScaled (FAST-LIO2's and I2EKF-LO's,
// laserMapping.cpp): at every association, a plane only if s = 1 - 0.9 |z| / sqrt(|p|) > 0.9,
// |z| the point's residual and |p| its range, so a far point may lie farther off its plane; no
// residual gate. kModelDeviation: as kResidual, with the gate from how far the motion model's
// predictions were off (KISS-ICP's adaptive threshold, MotorizedLidarOdometry sets it).
enum class AssociationGate { kResidual, kRangeScaled, kModelDeviation };

struct UpdateOptions {
  std::size_t nearest_neighbours = 5;
  double plane_max_point_distance = 0.1;  // m
  double plane_min_spread_ratio = 0.0;    // see OdometryConfig
  double max_neighbour_distance = 1.0;    // m, the k-th neighbour must be closer than this
  double measurement_variance = 0.001;    // m^2
  int max_iterations = 10;
  double convergence_rotation = 5e-5;     // rad, step size that ends the iterations
  double convergence_translation = 5e-4;  // m
  // Planes are re-associated once the iterate has moved more than these since the last
  // association; re-associating after every small step makes the plane set flicker.
  double reassociation_rotation = 3e-3;     // rad
  double reassociation_translation = 3e-2;  // m
  std::size_t min_correspondences = 30;     // fewer: the update is skipped
  AssociationGate association_gate = AssociationGate::kResidual;
  // kResidual: residuals beyond max(min_residual_gate, 3 robust standard deviations) are left out.
  double min_residual_gate = 0.05;  // m
  // kModelDeviation: the gate (m), at least min_residual_gate; by default KISS-ICP's start, 3 x its
  // initial 2 m, which MotorizedLidarOdometry keeps until a deviation is counted.
  double model_deviation_gate = 6.0;
  // Skip a plane whose map points were mostly seen from its other side (see the header).
  bool match_seen_side_only = true;
  // Degeneracy (degeneracy.hpp): directions whose scaled information eigenvalue (an effective
  // number of points) is below degeneracy_threshold are degenerate. With project_degenerate, the
  // degenerate directions of the whole state get no information from the measurements and the
  // motion prior decides them; either way both analyses are reported in the summary.
  bool project_degenerate = false;
  // The frame's own velocity (OdometryConfig::frame_velocity_std_linear and _angular): standard
  // deviations of its deviation from the filter's velocity within the frame; both 0 (the paper's
  // LO): no deviation, the filter's velocity deskews the frame.
  double frame_velocity_std_linear = 0.0;   // m/s
  double frame_velocity_std_angular = 0.0;  // rad/s
  double degeneracy_threshold = 20.0;
  DegeneracyScales degeneracy_scales;
  // The degeneracy analyses judge the information of the whole downsampled scan, estimated as this
  // times that of the points registered: a registration budget registers an even sample of the
  // scan (OdometryConfig::max_registration_points), and the threshold counts the scan's points,
  // not the budget's. 1 without a budget.
  double degeneracy_information_scale = 1.0;
};

struct UpdateSummary {
  bool applied = false;    // false: too few correspondences or a non-finite step; x- kept
  bool converged = false;  // the last step was below the convergence thresholds
  int iterations = 0;
  int associations = 0;  // how many times the planes were found anew (the costliest part)
  std::size_t correspondences = 0;
  // Information of the pose from the last linearisation, unit weight, [rotation, translation]:
  // Lambda = sum_i J_i J_i^T (as in docs/dev/architecture.md section 1, UA-MPC step 3).
  Matrix6d pose_information = Matrix6d::Zero();
  // Eigen-analyses at the last linearisation: of the pose alone (what is reported) and of the
  // whole state (the directions the measurements were kept out of). Both judge the information
  // net of what the planes' own noise adds (planeNoiseInformation in the source): a noisy normal
  // lends every direction a little, whether a surface constrains it or not.
  PoseDegeneracy pose_degeneracy;
  StateDegeneracy state_degeneracy;
  // The frame's deviation from the updated velocity, when UpdateOptions ask for one: the deskew
  // of this frame's points (deskewToWorld) takes it.
  std::optional<FrameDeviation> frame_deviation;
};

class IteratedEkf {
 public:
  IteratedEkf(const BaseState& initial, const Matrix12d& covariance);

  // Process noise densities: linear (m/s)^2/s, angular (rad/s)^2/s.
  void predict(double dt, double linear_process_noise, double angular_process_noise);
  // LiDAR-inertial prediction (inertial.hpp): the steps integrated in turn,
  //   a_W = R f_B + g,  R <- R Exp(omega dt),  r <- r + v dt + a_W dt^2 / 2,  v <- v + a_W dt,
  // with the error-state Jacobian of each step (dtheta <- Exp(-omega dt) dtheta,
  // dr <- dr + dv dt, dv <- dv - R [f_B]x dtheta dt) and the IMU's white noise as process noise.
  // The angular velocity becomes the steps' mean rate, with noise.rate_variance: the scan's
  // deskew uses it, the gyro has measured it.
  void predictInertial(const std::vector<InertialStep>& steps, const InertialNoise& noise);
  UpdateSummary update(const std::vector<TimedPoint>& points, const LocalMap& map, const UpdateOptions& options);

  const BaseState& state() const { return state_; }
  const Matrix12d& covariance() const { return covariance_; }

 private:
  // The pose and state degeneracy of the last linearisation, into the summary.
  static void reportDegeneracy(const Matrix12d& information, const Matrix12d& surface_information,
                               const UpdateOptions& options, UpdateSummary& summary);
  BaseState state_;
  Matrix12d covariance_;
};

}  // namespace uampc::lo
