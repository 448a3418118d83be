#include "uampc/lo/iterated_ekf.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "uampc/frames/gravity.hpp"
#include "uampc/lo/normal_equations.hpp"
#include "uampc/lo/plane_fit.hpp"
#include "uampc/lo/so3.hpp"
#include "uampc/lo/voxel_downsample.hpp"

namespace uampc::lo {

namespace {

// Whether the plane's map points were mostly seen from the other side than the sensor at
// viewpoint sees the point q from (views: unit directions from each neighbour to the sensor that
// saw it). Views nearly along the plane (within ~6 degrees) do not vote.
bool seenFromOtherSide(const Plane& plane, const std::vector<Eigen::Vector3f>& views, const Eigen::Vector3d& q,
                       const Eigen::Vector3d& viewpoint) {
  const double side = plane.normal.dot(viewpoint - q);
  int same = 0, other = 0;
  for (const auto& v : views) {
    const double s = plane.normal.dot(v.cast<double>());
    if (std::abs(s) < 0.1) continue;
    ((s > 0.0) == (side > 0.0) ? same : other) += 1;
  }
  return other > same;
}

// x (-) x_prior, in the error-state order [dtheta, dr, dv, dw].
Vector12d boxMinus(const BaseState& x, const BaseState& prior) {
  Vector12d d;
  d.segment<3>(0) = logSO3(prior.R_WB.transpose() * x.R_WB);
  d.segment<3>(3) = x.r_WB - prior.r_WB;
  d.segment<3>(6) = x.v_W - prior.v_W;
  d.segment<3>(9) = x.w_B - prior.w_B;
  return d;
}

// x (+) dx.
BaseState boxPlus(const BaseState& x, const Vector12d& dx) {
  BaseState out = x;
  out.R_WB = x.R_WB * expSO3(dx.segment<3>(0));
  // Keep R orthonormal over long runs.
  out.R_WB = Eigen::Quaterniond(out.R_WB).normalized().toRotationMatrix();
  out.r_WB += dx.segment<3>(3);
  out.v_W += dx.segment<3>(6);
  out.w_B += dx.segment<3>(9);
  return out;
}

bool finite(const BaseState& x) {
  return x.R_WB.allFinite() && x.r_WB.allFinite() && x.v_W.allFinite() && x.w_B.allFinite();
}

}  // namespace

IteratedEkf::IteratedEkf(const BaseState& initial, const Matrix12d& covariance)
    : state_(initial), covariance_(covariance) {}

void IteratedEkf::predict(double dt, double linear_process_noise, double angular_process_noise) {
  const Eigen::Vector3d phi = state_.w_B * dt;
  // State prediction x- = f(x): constant velocity.
  state_.R_WB = state_.R_WB * expSO3(phi);
  state_.r_WB += state_.v_W * dt;
  // Covariance prediction P- = F P F^T + Q, F the error-state Jacobian of f.
  Matrix12d F = Matrix12d::Identity();
  F.block<3, 3>(0, 0) = expSO3(-phi);
  F.block<3, 3>(0, 9) = rightJacobianSO3(phi) * dt;
  F.block<3, 3>(3, 6) = Eigen::Matrix3d::Identity() * dt;
  // Q: the velocity random walk integrated over dt (continuous white-noise-acceleration model):
  // the velocity gains q dt, the pose it drives gains q dt^3 / 3, correlated by q dt^2 / 2.
  // Leaving out the pose blocks made the predicted rotation ten times too certain: the filter
  // then could not follow an angular acceleration (a handheld turn stopping within 0.3 s).
  Matrix12d Q = Matrix12d::Zero();
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (const int pose_block : {0, 3}) {  // rotation with angular velocity, position with velocity
    const int velocity_block = pose_block + 6;
    const double q = pose_block == 0 ? angular_process_noise : linear_process_noise;
    Q.block<3, 3>(pose_block, pose_block) = q * dt * dt * dt / 3.0 * I;
    Q.block<3, 3>(pose_block, velocity_block) = q * dt * dt / 2.0 * I;
    Q.block<3, 3>(velocity_block, pose_block) = q * dt * dt / 2.0 * I;
    Q.block<3, 3>(velocity_block, velocity_block) = q * dt * I;
  }
  covariance_ = F * covariance_ * F.transpose() + Q;
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
}

void IteratedEkf::predictInertial(const std::vector<InertialStep>& steps, const InertialNoise& noise) {
  const Eigen::Vector3d gravity_W = frames::gravityInWorld();
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  Eigen::Vector3d rate_sum = Eigen::Vector3d::Zero();
  double duration = 0.0;
  for (const InertialStep& step : steps) {
    const double dt = step.dt;
    const Eigen::Vector3d phi = step.angular_velocity_B * dt;
    Matrix12d F = Matrix12d::Identity();
    F.block<3, 3>(0, 0) = expSO3(-phi);
    F.block<3, 3>(3, 6) = I * dt;
    F.block<3, 3>(6, 0) = -state_.R_WB * hat(step.specific_force_B) * dt;
    Matrix12d Q = Matrix12d::Zero();
    Q.block<3, 3>(0, 0) = noise.gyro_noise_density * noise.gyro_noise_density * dt * I;
    Q.block<3, 3>(6, 6) = noise.accel_noise_density * noise.accel_noise_density * dt * I;
    covariance_ = F * covariance_ * F.transpose() + Q;
    const Eigen::Vector3d a_W = state_.R_WB * step.specific_force_B + gravity_W;
    state_.r_WB += state_.v_W * dt + 0.5 * a_W * dt * dt;
    state_.v_W += a_W * dt;
    state_.R_WB = state_.R_WB * expSO3(phi);
    rate_sum += phi;
    duration += dt;
  }
  state_.R_WB = Eigen::Quaterniond(state_.R_WB).normalized().toRotationMatrix();
  if (duration > 0.0) state_.w_B = rate_sum / duration;
  // The rate is the gyro's, not a consequence of the earlier state: no correlation is kept.
  covariance_.block<3, 12>(9, 0).setZero();
  covariance_.block<12, 3>(0, 9).setZero();
  covariance_.block<3, 3>(9, 9) = noise.rate_variance * I;
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
}

namespace {

using Matrix18d = Eigen::Matrix<double, 18, 18>;
using Vector18d = Eigen::Matrix<double, 18, 1>;

// FAST-LIO2's gate (laserMapping.cpp of FAST-LIO2 and I2EKF-LO): s = 1 - 0.9 |z| / sqrt(|p|) > 0.9,
// z the residual and |p| the range (the LiDAR sits on the motor axis, at the base origin within
// centimetres: the point's norm in B).
bool withinRangeScaledGate(const Plane& plane, const Eigen::Vector3d& q_W, const TimedPoint& point) {
  const double residual = plane.normal.dot(q_W) + plane.offset;
  return 1.0 - 0.9 * std::abs(residual) / std::sqrt(point.p_B.norm()) > 0.9;
}

// Data association at the iterate x: each point with the plane through its k nearest map points,
// if they are near enough, planar, and (options.match_seen_side_only) seen from the point's side.
// spreads: how each plane's normal tilts, in the same order (apart, so the hot loops stay lean).
void associate(const std::vector<TimedPoint>& points, const FrameDeskew& deskew, const LocalMap& map,
               const UpdateOptions& options, std::vector<Correspondence>& correspondences,
               std::vector<PlaneSpread>& spreads) {
  const double max_neighbour_distance2 = options.max_neighbour_distance * options.max_neighbour_distance;
  std::vector<Eigen::Vector3d> neighbours;
  std::vector<Eigen::Vector3f> views;
  neighbours.reserve(options.nearest_neighbours);
  views.reserve(options.nearest_neighbours);
  correspondences.clear();
  spreads.clear();
  PlaneSpread spread;
  std::vector<Eigen::Vector3d> queries;
  queries.reserve(points.size());
  for (const TimedPoint& point : points) queries.push_back(deskew.toWorld(point));
  LocalMap::Search search(map, queries);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const TimedPoint& point = points[i];
    const Eigen::Vector3d& q = queries[i];
    if (search.next(options.nearest_neighbours, neighbours, &views) < options.nearest_neighbours) continue;
    if ((neighbours.back() - q).squaredNorm() > max_neighbour_distance2) continue;
    const std::optional<Plane> plane =
        fitPlane(neighbours, options.plane_max_point_distance, &spread, options.plane_min_spread_ratio);
    if (!plane) continue;
    // The sensor is at the base origin (the rigs we model carry the LiDAR on the motor axis
    // within centimetres of it, and nothing that near is seen), at the point's time.
    if (options.match_seen_side_only && seenFromOtherSide(*plane, views, q, deskew.originAt(point.tau))) continue;
    if (options.association_gate == AssociationGate::kRangeScaled && !withinRangeScaledGate(*plane, q, point)) continue;
    correspondences.push_back({&point, *plane});
    spreads.push_back(spread);
  }
}

// Gate: a residual far beyond the typical one is a wrong plane (the point lies on a surface the
// map has not seen yet, or across an edge), not noise; left in, a few such points at weight
// 1/sigma^2 bias the pose by millimetres to centimetres. The typical residual is 1.4826 * median
// |z| (robust standard deviation); the gate is 3 of those, at least min_gate.
double residualGate(const Eigen::VectorXd& z, double min_gate) {
  std::vector<double> magnitudes(z.data(), z.data() + z.size());
  for (double& m : magnitudes) m = std::abs(m);
  const auto middle = magnitudes.begin() + static_cast<std::ptrdiff_t>(magnitudes.size() / 2);
  std::nth_element(magnitudes.begin(), middle, magnitudes.end());
  return std::max(min_gate, 3.0 * 1.4826 * *middle);
}

// The gate of the gated iterations: the residuals' own (above), the one the odometry handed in
// (kModelDeviation), or none (kRangeScaled gates at association already).
double gateFor(const UpdateOptions& options, const Eigen::VectorXd& z) {
  switch (options.association_gate) {
    case AssociationGate::kResidual:
      return residualGate(z, options.min_residual_gate);
    case AssociationGate::kModelDeviation:
      return std::max(options.min_residual_gate, options.model_deviation_gate);
    case AssociationGate::kRangeScaled:
      break;
  }
  return std::numeric_limits<double>::infinity();
}

// What the planes' own noise adds to the unit-weight information H^T H of the state (12x12).
// A row is J_i = A_i n_i, linear in the plane's normal (A_i: 12x3, below). A normal fitted to a few
// noisy map points is tilted at random, n = n_true + dn with E[dn dn^T] = sigma^2 C_i (C_i:
// spreadInverse), so each row adds sigma^2 A_i C_i A_i^T on average: information along
// directions no surface constrains. In a plain corridor with 2 cm of range noise that is 20-30
// effective points along the axis, which hid its degeneracy in 91 % of the frames
// (docs/results/lo-degenerate-geometry.md, "The plain corridor"). sigma^2 is the median of the
// planes' own estimates: one plane's scatter also holds whatever bend of the surface it spans (an
// edge within the 0.1 m tolerance), which is not noise, and with those the sum came out up to twice
// what the corridor's axis had. Rows the gate dropped add nothing. An expectation, so it is
// estimated from every kStride-th row (the rows are in spatial order, so those spread over the
// whole scan), times kStride: a quarter of the cost, about 0.5 ms a frame.
Matrix12d planeNoiseInformation(const std::vector<Correspondence>& correspondences,
                                const std::vector<PlaneSpread>& spreads, const Eigen::VectorXd& z, double gate,
                                const BaseState& x, const FrameDeviation* deviation) {
  constexpr std::size_t kStride = 4;
  Matrix12d noise = Matrix12d::Zero();
  // After a re-association that found too few planes, z is still the previous set's: nothing to
  // pair its rows with.
  if (static_cast<std::size_t>(z.size()) != correspondences.size()) return noise;
  auto used = [&](std::size_t i) {
    return spreads[i].scatter_variance > 0.0 && !beyondGate(z(static_cast<Eigen::Index>(i)), gate);
  };
  std::vector<double> variances;
  for (std::size_t i = 0; i < correspondences.size(); i += kStride) {
    if (used(i)) variances.push_back(spreads[i].scatter_variance);
  }
  if (variances.empty()) return noise;
  const auto middle = variances.begin() + static_cast<std::ptrdiff_t>(variances.size() / 2);
  std::nth_element(variances.begin(), middle, variances.end());
  const double sigma2 = *middle;
  const FrameDeskew deskew(x, deviation);
  const Eigen::Matrix3d R_BW = x.R_WB.transpose();
  Eigen::Matrix<double, 12, 3> A;
  for (std::size_t i = 0; i < correspondences.size(); i += kStride) {
    if (!used(i)) continue;
    const Correspondence& c = correspondences[i];
    const TimedPoint& point = *c.point;
    const FrameDeskew::Rotation E = deskew.rotation(point.tau);
    const Eigen::Vector3d s = E * point.p_B;
    // Rotation: s x n_B = [s]x R_BW n. Angular velocity: tau p x E^T n_B = tau E^T [s]x R_BW n.
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d rotation_column = s.cross(R_BW.col(k));
      A.block<3, 1>(0, k) = rotation_column;
      A.block<3, 1>(9, k) = point.tau * E.transposeTimes(rotation_column);
    }
    A.block<3, 3>(3, 0).setIdentity();                              // position: n
    A.block<3, 3>(6, 0) = point.tau * Eigen::Matrix3d::Identity();  // linear velocity: tau n
    // Coefficient-wise products: for these fixed sizes Eigen would otherwise pack them for its
    // large-matrix kernel, which cost more than the sums themselves.
    const Eigen::Matrix<double, 12, 3> AC = A.lazyProduct(spreadInverse(c.plane, spreads[i]));
    noise.noalias() += AC.lazyProduct(A.transpose());
  }
  return (sigma2 * static_cast<double>(kStride)) * noise;
}

// The Gauss-Newton step with the frame's deviation e as 6 more unknowns (see the header): the
// system [A_xx A_xe; A_xe^T A_ee] (dx, de) = (b_x, b_e). state_information: the state's
// information with e marginalised out, A_xx - A_xe A_ee^-1 A_xe^T.
Vector18d stepWithDeviation(const Matrix12d& A_xx, const Eigen::Matrix<double, 12, 6>& A_xe, const Matrix6d& A_ee,
                            const Vector12d& b_x, const Vector6d& b_e, Matrix12d& state_information) {
  Matrix18d A;
  A << A_xx, A_xe, A_xe.transpose(), A_ee;
  Vector18d b;
  b << b_x, b_e;
  state_information = A_xx - A_xe * A_ee.ldlt().solve(A_xe.transpose());
  return A.ldlt().solve(b);
}

// The frame's own velocity, when asked for (see the header): its deviation from the state's, and
// that deviation's prior information, diag(1 / std^2); a std of 0 ties that part.
std::optional<FrameDeviation> frameDeviationOf(const std::vector<TimedPoint>& points, const UpdateOptions& options,
                                               Vector6d& deviation_prior) {
  deviation_prior = Vector6d::Zero();
  if (!(options.frame_velocity_std_linear > 0.0 || options.frame_velocity_std_angular > 0.0)) return std::nullopt;
  auto information = [](double std) { return std > 0.0 ? 1.0 / (std * std) : 1e12; };
  deviation_prior << Eigen::Vector3d::Constant(information(options.frame_velocity_std_linear)),
      Eigen::Vector3d::Constant(information(options.frame_velocity_std_angular));
  return FrameDeviation{middleTime(points), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
}

// Directions the scan cannot see get none of its information (Zhang et al. 2016): projected out of
// the state's normal equations with the degeneracy analysis's projector.
void projectOutDegenerateDirections(const Matrix12d& pi, bool with_frame, NormalEquations& n) {
  n.HtH = (pi.transpose() * n.HtH * pi).eval();
  n.Htz = (pi.transpose() * n.Htz).eval();
  if (with_frame) n.HtHe = (pi.transpose() * n.HtHe).eval();
}

// The Gauss-Newton step of the IEKF in information form (see the header): dx for the state, and
// the frame's deviation moved by its own part of the step when there is one. posterior_information
// becomes the state's information at this linearisation.
Vector12d gaussNewtonStep(const NormalEquations& n, const Matrix12d& prior_information, const Vector12d& from_prior,
                          double inverse_variance, const Vector6d& deviation_prior, FrameDeviation* deviation,
                          Matrix12d& posterior_information) {
  const Matrix12d A = prior_information + inverse_variance * n.HtH;
  const Vector12d b = -inverse_variance * n.Htz - prior_information * from_prior;
  if (!deviation) {
    posterior_information = A;
    return A.ldlt().solve(b);
  }
  // With the frame's deviation as 6 more unknowns.
  Vector6d e;
  e << deviation->dv_W, deviation->dw_B;
  const Matrix6d A_ee = Matrix6d(deviation_prior.asDiagonal()) + inverse_variance * n.Hee;
  const Vector6d b_e = -inverse_variance * n.Hez - deviation_prior.cwiseProduct(e);
  const Vector18d step = stepWithDeviation(A, inverse_variance * n.HtHe, A_ee, b, b_e, posterior_information);
  deviation->dv_W += step.segment<3>(12);
  deviation->dw_B += step.segment<3>(15);
  return step.head<12>();
}

}  // namespace

UpdateSummary IteratedEkf::update(const std::vector<TimedPoint>& points, const LocalMap& map,
                                  const UpdateOptions& options) {
  UpdateSummary summary;
  const BaseState prior = state_;
  const Matrix12d prior_information = covariance_.ldlt().solve(Matrix12d::Identity());
  const double inverse_variance = 1.0 / options.measurement_variance;

  BaseState x = prior;
  Matrix12d posterior_information = prior_information;
  std::vector<Correspondence> correspondences;
  std::vector<PlaneSpread> spreads;  // parallel to correspondences
  correspondences.reserve(points.size());
  spreads.reserve(points.size());
  // Query the map in spatial (Morton) order: successive queries then share most of their map
  // blocks, which stay in cache. Same result as scan order, fewer cache misses.
  const std::vector<TimedPoint> ordered = spatialOrder(points, map.voxelSize());
  Vector6d deviation_prior;
  std::optional<FrameDeviation> deviation = frameDeviationOf(points, options, deviation_prior);
  const FrameDeviation* frame = deviation ? &*deviation : nullptr;
  bool reassociate = true;
  bool gated = false;  // the residual gate is applied once the ungated iterations converged
  double gate = std::numeric_limits<double>::infinity();
  double rotation_since_association = 0.0, translation_since_association = 0.0;
  Linearisation linearisation;  // point-to-plane residuals and rows
  Matrix12d information = Matrix12d::Zero();  // unit-weight H^T H of the last linearisation
  BaseState linearised_at = x;                // and where it was linearised
  // What the planes' noise adds to information, once known for the last linearisation (every
  // linearisation needs it only with project_degenerate; the report needs it once).
  std::optional<Matrix12d> information_noise;

  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    if (reassociate) {
      rotation_since_association = translation_since_association = 0.0;
      associate(ordered, FrameDeskew(x, frame), map, options, correspondences, spreads);
      ++summary.associations;
      summary.correspondences = correspondences.size();
      if (correspondences.size() < options.min_correspondences) break;  // keep last good iterate
    }
    linearise(correspondences, x, frame, linearisation);
    // The gate is set once, when the gated iterations start, so that they converge on a fixed
    // set of residuals.
    if (gated && !std::isfinite(gate)) gate = gateFor(options, linearisation.z);
    NormalEquations normal = normalEquations(linearisation, frame, gate);
    summary.correspondences = normal.used;
    if (normal.used < options.min_correspondences) break;
    information = normal.HtH;
    linearised_at = x;
    information_noise.reset();
    // The analysis of what the scan cannot see is redone at every linearisation only when it
    // decides the step; for the report it is made once, after the loop.
    if (options.project_degenerate) {
      information_noise = planeNoiseInformation(correspondences, spreads, linearisation.z, gate, x, frame);
      summary.state_degeneracy =
          analyseStateDegeneracy(options.degeneracy_information_scale * (normal.HtH - *information_noise),
                                 options.degeneracy_scales, options.degeneracy_threshold);
      if (summary.state_degeneracy.degenerate_directions > 0) {
        projectOutDegenerateDirections(summary.state_degeneracy.projector, frame != nullptr, normal);
      }
    }
    const Vector12d dx = gaussNewtonStep(normal, prior_information, boxMinus(x, prior), inverse_variance,
                                         deviation_prior, deviation ? &*deviation : nullptr, posterior_information);
    if (!dx.allFinite() || (frame && !(deviation->dv_W.allFinite() && deviation->dw_B.allFinite()))) {
      summary.applied = false;
      state_ = prior;
      return summary;
    }
    x = boxPlus(x, dx);
    summary.applied = true;
    summary.iterations = iteration + 1;
    const double step_rotation = dx.segment<3>(0).norm();
    const double step_translation = dx.segment<3>(3).norm();
    rotation_since_association += step_rotation;
    translation_since_association += step_translation;
    // Without the gate, converging to 10x the tolerance is enough: the gated iterations refine.
    const double tolerance_scale = gated ? 1.0 : 10.0;
    if (step_rotation < tolerance_scale * options.convergence_rotation &&
        step_translation < tolerance_scale * options.convergence_translation) {
      // Converged with every correspondence: now drop the outliers and converge again. Gating
      // earlier would drop the inliers of a direction the prediction got wrong.
      if (gated) {
        summary.converged = true;
        break;
      }
      gated = true;
    }
    // Re-associating after tiny steps only makes the set of planes flicker (a 2-cycle between
    // two sets); the association is redone only once the state has moved enough since.
    reassociate = rotation_since_association > options.reassociation_rotation ||
                  translation_since_association > options.reassociation_translation;
  }
  if (summary.applied) {
    if (!information_noise)
      information_noise = planeNoiseInformation(correspondences, spreads, linearisation.z, gate, linearised_at, frame);
    reportDegeneracy(information, options.degeneracy_information_scale * (information - *information_noise), options,
                     summary);
  }
  if (!summary.applied || !finite(x)) {
    summary.applied = false;
    state_ = prior;
    return summary;
  }
  state_ = x;
  summary.frame_deviation = deviation;
  // Covariance update P+ = (I - K H) P- = (P-^-1 + H^T H / sigma^2)^-1 (with a frame deviation, the
  // information of the state with the deviation marginalised out).
  covariance_ = posterior_information.ldlt().solve(Matrix12d::Identity());
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
  return summary;
}

// The information of the last linearisation, before any projection: what the scan saw, and the
// part of it that surfaces, not the planes' noise, provide (what the degeneracy analyses judge).
void IteratedEkf::reportDegeneracy(const Matrix12d& information, const Matrix12d& surface_information,
                                   const UpdateOptions& options, UpdateSummary& summary) {
  summary.pose_information = information.topLeftCorner<6, 6>();
  summary.pose_degeneracy = analysePoseDegeneracy(surface_information.topLeftCorner<6, 6>(), options.degeneracy_scales,
                                                  options.degeneracy_threshold);
  if (!options.project_degenerate) {
    summary.state_degeneracy =
        analyseStateDegeneracy(surface_information, options.degeneracy_scales, options.degeneracy_threshold);
  }
}

}  // namespace uampc::lo
