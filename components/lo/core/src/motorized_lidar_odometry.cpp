#include "uampc/lo/motorized_lidar_odometry.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "uampc/lo/derotation.hpp"
#include "uampc/lo/deskew.hpp"
#include "uampc/lo/voxel_downsample.hpp"

namespace uampc::lo {

namespace {

void addWarning(std::string& warning, const std::string& text) {
  if (!warning.empty()) warning += "; ";
  warning += text;
}

}  // namespace

bool MotorizedLidarOdometry::addImu(const ImuReading& reading) {
  if (!usableImuReading(reading, newestImuTime())) return false;
  imu_.push_back(reading);
  // Bounded whatever the scans do: at 200 Hz, 10 s of readings.
  if (imu_.size() > 2000) imu_.pop_front();
  return true;
}

double MotorizedLidarOdometry::newestImuTime() const {
  return imu_.empty() ? -std::numeric_limits<double>::infinity() : imu_.back().time;
}

bool MotorizedLidarOdometry::implausibleMotion(const IteratedEkf& predicted, const BaseState& updated,
                                               double dt) const {
  // The update's change of velocity against the prediction's (constant-velocity or inertial) is
  // what the scan demands of the frame. Allowed: the acceleration limit over the frame, plus 3 standard deviations of
  // the predicted velocity (a velocity not known yet, as at the start, may change by what it is unsure of).
  const Matrix12d& P = predicted.covariance();
  const double linear_std = std::sqrt(P.diagonal().segment<3>(6).maxCoeff());
  const double angular_std = std::sqrt(P.diagonal().segment<3>(9).maxCoeff());
  const BaseState& before = predicted.state();
  return (updated.v_W - before.v_W).norm() > config_.max_linear_acceleration * dt + 3.0 * linear_std ||
         (updated.w_B - before.w_B).norm() > config_.max_angular_acceleration * dt + 3.0 * angular_std;
}

const char* toString(OdometryStatus status) {
  switch (status) {
    case OdometryStatus::kInitialised:
      return "initialised";
    case OdometryStatus::kTracking:
      return "tracking";
    case OdometryStatus::kDegenerate:
      return "degenerate";
    case OdometryStatus::kPredictedOnly:
      return "predicted-only";
    case OdometryStatus::kRejected:
      return "rejected";
    case OdometryStatus::kLost:
      return "lost";
  }
  return "unknown";
}

UpdateOptions updateOptionsFrom(const OdometryConfig& config) {
  UpdateOptions options;
  options.nearest_neighbours = config.nearest_neighbours;
  options.plane_max_point_distance = config.plane_max_point_distance;
  options.plane_min_spread_ratio = config.plane_min_spread_ratio;
  options.max_neighbour_distance = config.max_neighbour_distance;
  options.association_gate = config.association_gate;
  options.match_seen_side_only = config.match_seen_side_only;
  options.measurement_variance = config.measurement_variance;
  options.max_iterations = config.max_iterations;
  options.min_correspondences = config.min_correspondences;
  options.project_degenerate = config.degeneracy_aware;
  // degeneracy_aware leaves the velocities' weak directions to the prior itself; together with a
  // frame's own velocity the two fight (lo_replay: KTH lost at once, the campus at 101.8 s:
  // docs/results/lo-degenerate-geometry.md, "Each frame's own velocity"),
  // so with it each frame is deskewed with the filter's velocity, as before.
  if (!config.degeneracy_aware) {
    options.frame_velocity_std_linear = config.frame_velocity_std_linear;
    options.frame_velocity_std_angular = config.frame_velocity_std_angular;
  }
  options.degeneracy_threshold = config.degeneracy_threshold;
  options.degeneracy_scales = config.degeneracy_scales;
  return options;
}

MotorizedLidarOdometry::MotorizedLidarOdometry(const OdometryConfig& config)
    : config_(config),
      map_(config.map_voxel_size, config.map_radius, config.map_mean_points),
      accepted_poses_(config.velocity_reset_window) {}

OdometryResult MotorizedLidarOdometry::registerScan(const Scan& scan, const frames::MotorAngleTrack& motor) {
  OdometryResult result;
  DerotatedScan derotated = derotateScan(scan, motor, result);
  if (!filter_) {
    retimeForDeskew(derotated.points, config_.deskew, 0.0);
    return initialise(derotated, result);
  }

  const double end_time = derotated.points.empty() ? scan.stamp : derotated.end_time;
  const double dt = end_time - last_time_;
  retimeForDeskew(derotated.points, config_.deskew, dt);
  if (!(dt > 0.0)) {
    result.status = OdometryStatus::kRejected;
    addWarning(result.warning, "scan ends at " + std::to_string(end_time) + " s, not after the previous one (" +
                                   std::to_string(last_time_) + " s): ignored");
    fillState(result);
    return result;
  }
  const IteratedEkf before_prediction = *filter_;
  predict(end_time, dt, motor, result);
  if (end_time <= first_time_ + config_.initial_map_time) return extendInitialMap(derotated, end_time, result);
  const IteratedEkf predicted = *filter_;

  std::vector<TimedPoint> keypoints = voxelDownsample(derotated.points, config_.scan_voxel_size);
  const std::size_t downsampled = keypoints.size();
  keypoints = spatialSubset(std::move(keypoints), registrationBudget(downsampled), config_.map_voxel_size);
  result.points_used = keypoints.size();
  const double sampled_fraction =
      keypoints.empty() ? 1.0 : static_cast<double>(keypoints.size()) / static_cast<double>(downsampled);
  const UpdateSummary summary =
      correct(keypoints, sampled_fraction, before_prediction, predicted, end_time, dt, result);
  const bool lost = lostAt(end_time);
  if (lost && !lost_ && velocityResets(result)) resetVelocityAtLoss(end_time, result);
  lost_ = lost;
  result.velocity_resets = velocity_resets_;
  reportStatus(summary, keypoints.empty(), end_time, result);
  last_weakest_information_ = summary.applied ? std::max(0.0, result.min_information_eigenvalue) : 0.0;

  // The map grows with the registered scan, at full resolution (the map voxel grid downsamples).
  // Each point keeps the side it was seen from, taken from the base origin at the frame's end
  // (the LiDAR turns on the motor axis there; see the seen-side test in iterated_ekf.hpp).
  const FrameDeviation* deviation = summary.applied && summary.frame_deviation ? &*summary.frame_deviation : nullptr;
  const std::vector<Eigen::Vector3d> points_W = deskewToWorld(derotated.points, filter_->state(), deviation);
  if (summary.applied) {
    map_.insert(points_W, last_time_, filter_->state().r_WB);
    map_.removeFarFrom(filter_->state().r_WB);
  }
  result.registered_points_W.reserve(points_W.size());
  for (const auto& p : points_W) result.registered_points_W.push_back(p.cast<float>());
  fillState(result);
  return result;
}

// Every point into the base frame with the encoder angle at its own time (Eq. 1); what was
// dropped, counted and said.
DerotatedScan MotorizedLidarOdometry::derotateScan(const Scan& scan, const frames::MotorAngleTrack& motor,
                                                   OdometryResult& result) const {
  result.points_in = scan.points_L.size();
  DerotatedScan derotated = derotate(scan, motor, config_.calibration, config_.min_range, config_.max_range);
  result.dropped_non_finite = derotated.dropped_non_finite;
  result.dropped_range = derotated.dropped_range;
  result.dropped_outside_motor_track = derotated.dropped_outside_motor_track;
  if (derotated.dropped_outside_motor_track > 0) {
    addWarning(result.warning, std::to_string(derotated.dropped_outside_motor_track) +
                                   " points dropped: their time lies outside the motor track");
  }
  if (derotated.dropped_non_finite > 0) {
    addWarning(result.warning, std::to_string(derotated.dropped_non_finite) + " non-finite points dropped");
  }
  return derotated;
}

// First scan: the map starts at the initial pose (known exactly) and velocity.
OdometryResult MotorizedLidarOdometry::initialise(const DerotatedScan& derotated, OdometryResult result) {
  if (derotated.points.empty()) {
    result.status = OdometryStatus::kPredictedOnly;
    result.time = derotated.end_time;
    result.T_WB = config_.initial_pose;
    addWarning(result.warning, "no usable points: map not initialised yet");
    return result;
  }
  BaseState x;
  x.R_WB = config_.initial_pose.linear();
  x.r_WB = config_.initial_pose.translation();
  x.v_W = config_.initial_velocity_W;
  x.w_B = config_.initial_angular_velocity_B;
  filter_.emplace(x, initialCovariance());
  first_time_ = last_time_ = last_accepted_time_ = derotated.end_time;
  return addToInitialMap(derotated, std::move(result));
}

Matrix12d MotorizedLidarOdometry::initialCovariance() const {
  Matrix12d P = Matrix12d::Zero();
  P.diagonal().head<6>().setConstant(1e-8);
  P.diagonal().tail<6>().setConstant(config_.initial_velocity_variance);
  return P;
}

// Within initial_map_time of the first scan the rig moves as its initial state says (it stands
// still, in the scenes that use it): the prediction places the scan, and the state stays as sure
// as at the start, since nothing was learnt that could make it less so.
OdometryResult MotorizedLidarOdometry::extendInitialMap(const DerotatedScan& derotated, double end_time,
                                                        OdometryResult result) {
  const BaseState predicted = filter_->state();  // a copy: emplace destroys the filter first
  filter_.emplace(predicted, initialCovariance());
  last_accepted_time_ = end_time;
  return addToInitialMap(derotated, std::move(result));
}

// The scan, deskewed with the filter's state, into the map; reported as part of the initial map.
OdometryResult MotorizedLidarOdometry::addToInitialMap(const DerotatedScan& derotated, OdometryResult result) {
  const BaseState& x = filter_->state();
  // The initial state is known (docs/decisions/lo-initial-map.md): as good as an accepted pose.
  accepted_poses_.add(last_time_, x);
  last_accepted_.emplace(*filter_);
  const std::vector<Eigen::Vector3d> points_W = deskewToWorld(derotated.points, x);
  map_.insert(points_W, last_time_, x.r_WB);
  map_.removeFarFrom(x.r_WB);
  result.status = OdometryStatus::kInitialised;
  result.points_used = derotated.points.size();
  result.registered_points_W.reserve(points_W.size());
  for (const auto& p : points_W) result.registered_points_W.push_back(p.cast<float>());
  fillState(result);
  return result;
}

// The state carried to the scan's end: the IMU's readings over the frame, or else the
// constant-velocity model.
void MotorizedLidarOdometry::predict(double end_time, double dt, const frames::MotorAngleTrack& motor,
                                     OdometryResult& result) {
  const std::vector<InertialStep> steps = config_.use_imu
                                              ? inertialSteps(imu_, last_time_, end_time, motor, config_.calibration)
                                              : std::vector<InertialStep>{};
  if (!steps.empty()) {
    filter_->predictInertial(steps, config_.imu_noise);
    result.inertial_prediction = true;
  } else {
    filter_->predict(dt, config_.linear_process_noise, config_.angular_process_noise);
    if (config_.use_imu) addWarning(result.warning, "no IMU readings cover the frame: constant-velocity prediction");
  }
  last_time_ = end_time;
  while (!imu_.empty() && imu_.front().time < last_time_ - 0.1) imu_.pop_front();
}

// How many of the downsampled scan's points register (0: all): the budget, or more where the last
// frame's weakest direction needs them (OdometryConfig::registration_weakest_points).
std::size_t MotorizedLidarOdometry::registrationBudget(std::size_t downsampled_points) const {
  const auto budget = static_cast<std::size_t>(config_.max_registration_points);
  if (budget == 0 || config_.registration_weakest_points <= 0.0) return budget;
  if (!(last_weakest_information_ > 0.0)) return 0;
  const double needed =
      std::ceil(static_cast<double>(downsampled_points) * config_.registration_weakest_points / last_weakest_information_);
  return needed >= static_cast<double>(downsampled_points) ? 0 : std::max(budget, static_cast<std::size_t>(needed));
}

// The iterated update against the local map, undone if it needs an implausible acceleration.
UpdateSummary MotorizedLidarOdometry::correct(const std::vector<TimedPoint>& keypoints, double sampled_fraction,
                                              const IteratedEkf& before_prediction, const IteratedEkf& predicted,
                                              double end_time, double dt, OdometryResult& result) {
  UpdateSummary summary;
  if (!keypoints.empty()) {
    UpdateOptions options = updateOptionsFrom(config_);
    options.degeneracy_information_scale = 1.0 / sampled_fraction;
    // The IMU has measured how the base moved within the frame: no frame deviation from it. (With
    // it, an open field's unobservable directions took up the noise: 0.10 -> 0.23 m, measured in
    // degenerate_geometry_test.)
    if (result.inertial_prediction) options.frame_velocity_std_linear = options.frame_velocity_std_angular = 0.0;
    options.model_deviation_gate = modelDeviationGate();
    summary = filter_->update(keypoints, map_, options);
  }
  result.correspondences = summary.correspondences;
  result.iterations = summary.iterations;
  result.associations = summary.associations;
  // Once lost, the prediction is what went wrong: judging the scan by it would reject every
  // correction and keep the wrong velocity for good (KTH at 324.4 s: 100 deg/s held;
  // docs/results/lo-degenerate-geometry.md, "The mechanism").
  const bool lost_before = lostAt(end_time);
  if (summary.applied &&
      (beyondSpeedLimits(filter_->state(), config_.max_speed, config_.max_angular_speed) ||
       (!lost_before && implausibleMotion(predicted, filter_->state(), dt)))) {
    *filter_ = predicted;
    summary.applied = false;
    result.implausible_motion = true;
    ++rejected_updates_;
    if (velocityResets(result)) resetVelocityAfterRejection(before_prediction, dt, result);
  }
  if (summary.applied) {
    countModelDeviation(predicted.state(), filter_->state());
    last_accepted_time_ = end_time;
    accepted_poses_.add(end_time, filter_->state());
    last_accepted_.emplace(*filter_);
  }
  result.rejected_updates = rejected_updates_;
  return summary;
}

void MotorizedLidarOdometry::countModelDeviation(const BaseState& predicted, const BaseState& updated) {
  if (config_.association_gate != AssociationGate::kModelDeviation) return;
  const double theta = Eigen::AngleAxisd(predicted.R_WB.transpose() * updated.R_WB).angle();
  const double delta = (updated.r_WB - predicted.r_WB).norm() + 2.0 * config_.max_range * std::sin(0.5 * theta);
  constexpr double kSmallestCounted = 0.1;  // m, KISS-ICP's min_motion_th: a smaller deviation is noise
  if (delta <= kSmallestCounted) return;
  model_deviation_sse_ += delta * delta;
  ++model_deviations_;
}

double MotorizedLidarOdometry::modelDeviationGate() const {
  if (model_deviations_ == 0) return UpdateOptions{}.model_deviation_gate;
  return 3.0 * std::sqrt(model_deviation_sse_ / static_cast<double>(model_deviations_));
}

void MotorizedLidarOdometry::resetVelocityAfterRejection(const IteratedEkf& before_prediction, double dt,
                                                         OdometryResult& result) {
  std::ostringstream what;
  what << "velocity reset to the accepted poses' motion over " << config_.velocity_reset_window << " s";
  resetVelocity(before_prediction, std::nullopt, dt, what.str(), result);
}

void MotorizedLidarOdometry::resetVelocityAtLoss(double end_time, OdometryResult& result) {
  if (!last_accepted_) return;
  std::ostringstream what;
  what << "lost track: going on from the last accepted pose (" << last_accepted_time_
       << " s) with the accepted poses' motion";
  resetVelocity(*last_accepted_, config_.initial_velocity_variance, end_time - last_accepted_time_, what.str(),
                result);
}

void MotorizedLidarOdometry::resetVelocity(const IteratedEkf& from, std::optional<double> velocity_variance,
                                           double dt, const std::string& what, OdometryResult& result) {
  const std::optional<Motion> motion = accepted_poses_.meanMotion();
  if (!motion) return;
  IteratedEkf reset = withVelocity(from, *motion, velocity_variance);
  reset.predict(dt, config_.linear_process_noise, config_.angular_process_noise);
  *filter_ = reset;
  result.velocity_reset = true;
  ++velocity_resets_;
  std::ostringstream why;
  why << what << " (" << motion->v_W.norm() << " m/s, " << motion->w_B.norm() << " rad/s)";
  addWarning(result.warning, why.str());
}

// The scan's status (tracking, degenerate, predicted only, lost) and the warnings that explain it.
void MotorizedLidarOdometry::reportStatus(const UpdateSummary& summary, bool no_keypoints, double end_time,
                                          OdometryResult& result) const {
  if (!summary.applied) {
    result.status = OdometryStatus::kPredictedOnly;
    std::ostringstream why;
    if (no_keypoints) {
      why << "no usable points";
    } else if (result.implausible_motion) {
      why << "registration rejected: it needs an acceleration beyond " << config_.max_linear_acceleration
          << " m/s^2 or " << config_.max_angular_acceleration << " rad/s^2, or a speed beyond " << config_.max_speed
          << " m/s or " << config_.max_angular_speed << " rad/s";
    } else {
      why << "only " << summary.correspondences << " plane correspondences (need " << config_.min_correspondences
          << ")";
    }
    why << ": pose predicted by the constant-velocity model, uncertainty grows";
    addWarning(result.warning, why.str());
  } else {
    result.degeneracy = summary.pose_degeneracy;
    result.degenerate_state_directions = summary.state_degeneracy.degenerate_directions;
    result.min_information_eigenvalue = summary.pose_degeneracy.eigenvalues(0);
    if (summary.pose_degeneracy.degenerate_directions > 0) {
      result.status = OdometryStatus::kDegenerate;
      std::ostringstream why;
      why << "degenerate geometry: smallest pose information eigenvalue " << result.min_information_eigenvalue << " < "
          << config_.degeneracy_threshold << " (a direction is poorly constrained, e.g. a corridor or an open field)";
      addWarning(result.warning, why.str());
    } else {
      result.status = OdometryStatus::kTracking;
    }
    if (!summary.converged) {
      addWarning(result.warning,
                 "iterated EKF did not converge in " + std::to_string(config_.max_iterations) + " iterations");
    }
  }

  if (lostAt(end_time)) {
    result.status = OdometryStatus::kLost;
    result.lost = true;
    std::ostringstream why;
    why << "lost: no registration accepted for " << end_time - last_accepted_time_ << " s";
    addWarning(result.warning, why.str());
  }

  const double position_std = std::sqrt(filter_->covariance().block<3, 3>(3, 3).diagonal().maxCoeff());
  if (!(position_std <= config_.max_position_std)) {
    std::ostringstream why;
    why << "position standard deviation " << position_std << " m exceeds " << config_.max_position_std << " m";
    addWarning(result.warning, why.str());
  }
}

// The filter's state at the last scan's end.
void MotorizedLidarOdometry::fillState(OdometryResult& result) const {
  const BaseState& x = filter_->state();
  result.time = last_time_;
  result.T_WB = x.pose();
  result.linear_velocity_W = x.v_W;
  result.angular_velocity_B = x.w_B;
  result.covariance = filter_->covariance();
}

}  // namespace uampc::lo
