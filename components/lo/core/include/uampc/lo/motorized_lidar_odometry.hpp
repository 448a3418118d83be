// LiDAR odometry for a LiDAR spun by a motor: the composition of the core in one class.
//
// registerScan: de-rotate every point with the encoder angle at its own time (Eq. 1), voxel
// downsample, predict with the constant-velocity model, register to the local map with the
// iterated EKF (point-to-plane, deskew inside the measurement model, each frame with its own
// velocity about the filter's), then add the registered scan to the map and drop what is now out
// of range.
//
// The pose refers to the scan end: the time of the latest usable point (Result::time).
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/lo/acceleration_unit.hpp"
#include "uampc/lo/derotation.hpp"
#include "uampc/lo/inertial.hpp"
#include "uampc/lo/iterated_ekf.hpp"
#include "uampc/lo/local_map.hpp"
#include "uampc/lo/scan.hpp"
#include "uampc/lo/velocity_reset.hpp"

namespace uampc::lo {

// Defaults are the LO settings of docs/dev/architecture.md section 1 where it names them.
struct OdometryConfig {
  frames::MotorLidarCalibration calibration = frames::MotorLidarCalibration::referenceRig();
  Eigen::Isometry3d initial_pose = Eigen::Isometry3d::Identity();  // T_WB of the first scan
  // Velocity at the first scan (its deskew uses it). Zero: the robot starts at rest. In simulation
  // the component may take it from ground truth, as it takes the initial pose.
  Eigen::Vector3d initial_velocity_W = Eigen::Vector3d::Zero();          // m/s
  Eigen::Vector3d initial_angular_velocity_B = Eigen::Vector3d::Zero();  // rad/s

  double min_range = 0.5;        // m, measured in the LiDAR frame
  double max_range = 100.0;      // m
  double scan_voxel_size = 0.3;  // m
  // Registration budget: a downsampled scan with more points than this registers this many,
  // spread evenly over space (spatialSubset); the map still takes every point. 0: no budget, every
  // downsampled point registers (the LO before this option). Off until measured on every world
  // (docs/results/lo-degenerate-geometry.md, "A registration budget").
  int max_registration_points = 0;
  // With a budget, enough points register that the weakest pose direction keeps this many effective
  // points (the last frame's smallest pose information eigenvalue, degeneracy.hpp, scaled by the
  // share kept): where geometry is poor every point registers, the budget saves time where it is
  // rich. After a frame that registered nothing, the next registers every point. 0: the budget alone.
  double registration_weakest_points = 0.0;
  double map_voxel_size = 0.3;   // m
  // How many observations a map voxel's point averages (LocalMap); 1: the first point stays (the
  // LO before this option). 20 was chosen with tools/lo_replay at constant motor speeds only,
  // against 1 and 5 (docs/results/lo-degenerate-geometry.md, "The map's points"): with the scenes'
  // 2 cm range noise the worlds of the density profiles lost 7 of 12 runs with the first point, 1
  // with the mean of 20, while whole MCD trajectories and the indoor worlds held with either (worst
  // positions up to 0.9 m worse with the mean: an averaged voxel rounds the edges that hold a
  // corridor's axis).
  int map_mean_points = 20;
  double map_radius = 60.0;      // m, voxels farther than this from the base are dropped

  // Which time places each point in the deskew (deskew.hpp): its own by default; the reference's
  // LO places them by index (docs/results/table-1-reference-regime.md).
  DeskewMode deskew = DeskewMode::kTime;
  AssociationGate association_gate = AssociationGate::kResidual;  // iterated_ekf.hpp
  bool match_seen_side_only = true;  // docs/decisions/lo-seen-side-planes.md; I2EKF-LO has no such check

  std::size_t nearest_neighbours = 5;
  double plane_max_point_distance = 0.1;  // m, a plane is rejected if a neighbour is farther off
  // A plane is rejected if its points spread along their narrower in-plane direction less than
  // this fraction of along the wider (lambda_1 / lambda_2 of the scatter); 0: never. Thin patches
  // (points nearly on a line) leave the normal free to turn about the line: in the plain corridor
  // they were the x-facing planes near the sensor (docs/results/lo-degenerate-geometry.md, "The
  // plain corridor"). Off until measured on every world.
  double plane_min_spread_ratio = 0.0;
  double max_neighbour_distance = 1.0;    // m, the k-th neighbour must be closer (I2EKF-LO: sqrt(5))
  double measurement_variance = 0.001;    // m^2
  // Velocity random walk densities of the constant-velocity model, linear and angular (they can
  // be set apart). 0.1 for both: hand-held rigs (MCD KTH and TUHH) change their yaw rate by
  // ~70 deg/s within 0.2 s. Measured with tools/lo_replay over the whole KTH trajectory, constant
  // 3.6 rad/s: 0.1 / 0.1 holds (worst 0.63 m), 0.01 / 0.1 and 0.01 / 0.01 lose track at 328 s in
  // a degenerate stretch (docs/results/lo-degenerate-geometry.md, "What is still missed").
  double linear_process_noise = 0.1;   // (m/s)^2/s
  double angular_process_noise = 0.1;  // (rad/s)^2/s
  int max_iterations = 10;
  std::size_t min_correspondences = 30;

  double initial_velocity_variance = 1.0;  // (m/s)^2 and (rad/s)^2 at the first scan
  // The first map over this long (s; 0: the first scan alone): until the first scan's end plus
  // this, every scan is placed with the predicted state (the initial velocity, or the IMU) and
  // added to the map without registering, and the initial covariance is kept. The first
  // registration then meets the map the motor swept (one turn at 3.6 rad/s takes 1.75 s) instead of
  // one frame's, which in narrow fields of view and point maps slid along a weak direction and
  // threw the velocity off by metres per second with the rig at rest. Only for a rig known to move
  // as its initial state says over that time: one that stands still at the start (map_provider's
  // start_hold) (docs/decisions/lo-initial-map.md).
  double initial_map_time = 0.0;  // s
  // Degeneracy (degeneracy.hpp): a direction whose scaled information eigenvalue (an effective
  // number of points) is below degeneracy_threshold is degenerate. It is always analysed and
  // reported; with degeneracy_aware the scan does not move the estimate along the degenerate
  // directions of the whole state (pose and velocities), and the motion prior decides them.
  // Off by default: on a hand-held rig (MCD KTH) it also takes away the weak within-frame view
  // of the angular rate that fast turns need, and KTH, held without it, is lost at 219 s; on a
  // wheeled platform in poor geometry (the campus) it stops the yaw-rate runaway
  // (docs/results/lo-degenerate-geometry.md, "Why degeneracy_aware is off by default").
  double degeneracy_threshold = 20.0;
  DegeneracyScales degeneracy_scales;
  bool degeneracy_aware = false;
  // The frame's own velocity (iterated_ekf.hpp): standard deviations of how far a frame's deskew
  // velocity may differ from the filter's constant velocity, about the frame's middle. A frame
  // deskews itself with what its points say, but the state learns from that view at most about
  // one std per frame, and otherwise from how the pose moves from frame to frame. 0 and 0: the
  // filter's velocity deskews every frame, so what a frame says of its velocity goes into the
  // state at full weight (the paper's LO and ours until this option); where the walls are weak
  // that view is map error, and the yaw rate ran away (docs/results/lo-degenerate-geometry.md, "The
  // mechanism"). 0.3 m/s and 0.5 rad/s were chosen with tools/lo_replay at constant motor speeds
  // only (docs/results/lo-degenerate-geometry.md, "Each frame's own velocity"): the fewest losses
  // of track over whole runs of every world, noise-free and with the scenes' 2 cm range noise, and
  // the stretch of MCD KTH at 1.8 rad/s (280-340 s) that 0 and 0 lose and 0.1 and 0.2 lose with
  // noise; then the worst position. Not applied to a frame the IMU predicted (use_imu): its
  // readings measured the frame's motion; nor with degeneracy_aware, which leaves weak velocity
  // directions to the prior its own way.
  double frame_velocity_std_linear = 0.3;   // m/s
  double frame_velocity_std_angular = 0.5;  // rad/s
  // Warning: position standard deviation above this.
  double max_position_std = 1.0;  // m
  // Motion that cannot be: an update that changes the velocity by more than these accelerations
  // over the frame is rejected (the frame is predicted only and not added to the map) and
  // counted. A hand-held rig reaches 6 rad/s^2 (MCD KTH: 70 deg/s within 0.2 s) and a ground
  // vehicle rarely 1 g; a registration that needs more (beyond 3 standard deviations of the
  // predicted velocity) is a wrong one. Not applied while lost (see lost_after): the prediction
  // is then what is wrong.
  double max_linear_acceleration = 10.0;   // m/s^2
  double max_angular_acceleration = 20.0;  // rad/s^2
  // LiDAR-inertial mode (inertial.hpp): with use_imu, the IMU readings given to addImu replace
  // the constant-velocity prediction wherever they cover the time since the last scan.
  bool use_imu = false;
  InertialNoise imu_noise;
  // The unit of the readings' acceleration (acceleration_unit.hpp): the component scales them to
  // m/s^2 before addImu.
  AccelerationUnit imu_acceleration_unit = AccelerationUnit::kAuto;
  // Lost: no registration accepted for longer than this. The estimate then rests on the motion
  // model alone; the status says so until a scan registers again.
  double lost_after = 1.0;  // s
  // Velocity resets (velocity_reset.hpp, docs/decisions/lo-velocity-reset.md): when an update is
  // rejected for its acceleration or speed, the frame is predicted again from the previous one with
  // the mean motion of the accepted poses over this window, instead of with the velocity that the
  // scan disagreed with; at the start of a loss of track the LO goes back to the last accepted pose
  // and carries it to now with that motion, its velocity's variance initial_velocity_variance.
  // Not after an IMU prediction (the IMU measured the motion). 0: off (the LO before).
  double velocity_reset_window = 1.0;  // s
  // An update that leaves the velocity above these is rejected, lost or not: no rig we model moves
  // so (a hand-held turn reaches ~2 rad/s); a registration that says so is a wrong one.
  double max_speed = 40.0;          // m/s
  double max_angular_speed = 10.0;  // rad/s
};

enum class OdometryStatus {
  kInitialised,    // first usable scan, or one within initial_map_time of it: added to the map
                   // at initial_pose (or its prediction), not registered
  kTracking,       // registered
  kDegenerate,     // registered, but some direction is poorly constrained (see warning)
  kPredictedOnly,  // no update (no usable points, too few correspondences, or an implausible
                   // acceleration): motion model only, the scan is not added to the map
  kRejected,       // scan not newer than the previous one: state unchanged
  kLost,           // no registration accepted for more than lost_after: motion model only
};

const char* toString(OdometryStatus status);

struct OdometryResult {
  OdometryStatus status = OdometryStatus::kPredictedOnly;
  std::string warning;  // empty when all is well; otherwise says what and why

  double time = 0.0;  // s, the time T_WB refers to: the scan end
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity_W = Eigen::Vector3d::Zero();   // m/s, world frame
  Eigen::Vector3d angular_velocity_B = Eigen::Vector3d::Zero();  // rad/s, base frame
  // Error-state covariance, order [rotation (right perturbation of R_WB), position, linear
  // velocity, angular velocity]; rad, m, m/s, rad/s.
  Matrix12d covariance = Matrix12d::Zero();

  // Every usable point in the world frame, placed with the base pose at its own time (deskewed).
  std::vector<Eigen::Vector3f> registered_points_W;

  // Smallest eigenvalue of the scaled unit-weight pose information sum_i J_i J_i^T
  // (docs/dev/architecture.md section 1, UA-MPC step 3; scaled as in degeneracy.hpp); near zero
  // means some direction is unobservable. 0 when there was no update. degeneracy has every
  // eigenvalue and the degenerate directions.
  double min_information_eigenvalue = 0.0;
  PoseDegeneracy degeneracy;
  int degenerate_state_directions = 0;  // of the 12-dimensional state, velocities included
  std::size_t correspondences = 0;
  int iterations = 0;
  int associations = 0;  // plane searches of the update (IteratedEkf's UpdateSummary)
  bool implausible_motion = false;   // this scan's update was rejected for its acceleration or speed
  std::size_t rejected_updates = 0;  // such rejections since the start
  bool inertial_prediction = false;  // predicted with the IMU (else: constant velocity)
  bool lost = false;                 // see OdometryStatus::kLost
  bool velocity_reset = false;       // this frame's velocity was reset (OdometryConfig::velocity_reset_window)
  std::size_t velocity_resets = 0;   // such resets since the start

  std::size_t points_in = 0;
  std::size_t points_used = 0;  // after downsampling, fed to the filter
  std::size_t dropped_non_finite = 0;
  std::size_t dropped_range = 0;
  std::size_t dropped_outside_motor_track = 0;
};

// The iterated update's options as registerScan sets them from the config (tools that register a
// scan against the LO's map by hand, e.g. tools/u_check, use the same).
UpdateOptions updateOptionsFrom(const OdometryConfig& config);

class MotorizedLidarOdometry {
 public:
  explicit MotorizedLidarOdometry(const OdometryConfig& config = OdometryConfig{});

  // Throws std::invalid_argument when scan.points_L and scan.time_offsets differ in size.
  OdometryResult registerScan(const Scan& scan, const frames::MotorAngleTrack& motor);

  // An IMU reading (LiDAR-inertial mode). Refused (false) when a value or its time is not finite,
  // or it is not newer than the last one taken: the caller says so. Readings are kept until a
  // scan past them has been registered (at most 10 s of them).
  bool addImu(const ImuReading& reading);
  // Time of the newest reading taken, or -infinity before the first.
  double newestImuTime() const;

  // The local map in the world frame (LocalMap::points and pointsSince list it, with or without
  // the time each voxel was last observed).
  const LocalMap& localMap() const { return map_; }
  bool initialised() const { return filter_.has_value(); }
  const OdometryConfig& config() const { return config_; }

 private:
  // The steps of registerScan, in order.
  DerotatedScan derotateScan(const Scan& scan, const frames::MotorAngleTrack& motor, OdometryResult& result) const;
  OdometryResult initialise(const DerotatedScan& derotated, OdometryResult result);
  // A scan within initial_map_time of the first: into the map at the predicted state.
  OdometryResult extendInitialMap(const DerotatedScan& derotated, double end_time, OdometryResult result);
  Matrix12d initialCovariance() const;
  OdometryResult addToInitialMap(const DerotatedScan& derotated, OdometryResult result);
  void predict(double end_time, double dt, const frames::MotorAngleTrack& motor, OdometryResult& result);
  // sampled_fraction: the share of the downsampled scan that keypoints are (below 1 with a budget).
  // before_prediction: the filter at the previous frame's end, for a velocity reset.
  UpdateSummary correct(const std::vector<TimedPoint>& keypoints, double sampled_fraction,
                        const IteratedEkf& before_prediction, const IteratedEkf& predicted, double end_time, double dt,
                        OdometryResult& result);
  // The update was rejected: the frame predicted again with the accepted poses' motion.
  void resetVelocityAfterRejection(const IteratedEkf& before_prediction, double dt, OdometryResult& result);
  // A loss of track begins: back to the last accepted pose, carried to end_time with their motion.
  void resetVelocityAtLoss(double end_time, OdometryResult& result);
  // Both resets: the filter becomes `from` with the accepted poses' motion (velocity variance as
  // withVelocity takes it), predicted over dt; counted and explained by `what` in the warning.
  // Nothing happens when there is no accepted motion to reset to.
  void resetVelocity(const IteratedEkf& from, std::optional<double> velocity_variance, double dt,
                     const std::string& what, OdometryResult& result);
  // No registration accepted for longer than lost_after (OdometryStatus::kLost).
  bool lostAt(double end_time) const { return end_time - last_accepted_time_ > config_.lost_after; }
  bool velocityResets(const OdometryResult& result) const {
    return config_.velocity_reset_window > 0.0 && !result.inertial_prediction;
  }
  std::size_t registrationBudget(std::size_t downsampled_points) const;
  void reportStatus(const UpdateSummary& summary, bool no_keypoints, double end_time, OdometryResult& result) const;
  void fillState(OdometryResult& result) const;
  // KISS-ICP (Vizzo et al. 2023, Sec. III-C): delta = |t| + 2 r_max sin(theta / 2) between the
  // predicted and the updated pose, counted above 0.1 m (with that gate only); the gate is 3 sigma,
  // sigma = sqrt(mean delta^2), and UpdateOptions' default 6 m before the first.
  void countModelDeviation(const BaseState& predicted, const BaseState& updated);
  double modelDeviationGate() const;
  // Whether the update from predicted to updated needs an acceleration beyond the configured ones.
  bool implausibleMotion(const IteratedEkf& predicted, const BaseState& updated, double dt) const;

  OdometryConfig config_;
  LocalMap map_;
  std::optional<IteratedEkf> filter_;
  double last_time_ = 0.0;
  double first_time_ = 0.0;          // s, the end of the first scan (the map's start)
  double last_accepted_time_ = 0.0;  // s, the end of the last scan whose registration was accepted
  // The last registered frame's smallest pose information eigenvalue (effective points of the whole
  // scan); 0 after a frame that registered nothing.
  double last_weakest_information_ = 0.0;
  std::size_t rejected_updates_ = 0;
  AcceptedPoses accepted_poses_;
  std::optional<IteratedEkf> last_accepted_;  // the filter after the last accepted registration
  bool lost_ = false;                         // the previous frame was lost
  // KISS-ICP's adaptive threshold (AssociationGate::kModelDeviation): the sum of the squared
  // deviations of the accepted updates from their predictions, and how many were counted.
  double model_deviation_sse_ = 0.0;
  std::size_t model_deviations_ = 0;
  std::size_t velocity_resets_ = 0;
  std::deque<ImuReading> imu_;
};

}  // namespace uampc::lo
