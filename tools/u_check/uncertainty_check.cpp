#include "uncertainty_check.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "uampc/plots/paired_statistics.hpp"
#include "simulated_lidar.hpp"
#include "uampc/lo/derotation.hpp"
#include "uampc/lo/so3.hpp"
#include "uampc/lo/voxel_downsample.hpp"
#include "uampc/world/seeded_random.hpp"

namespace uampc::tools {
namespace {

lo::BaseState stateOf(const lo::OdometryResult& r) {
  lo::BaseState x;
  x.R_WB = r.T_WB.linear();
  x.r_WB = r.T_WB.translation();
  x.v_W = r.linear_velocity_W;
  x.w_B = r.angular_velocity_B;
  return x;
}

}  // namespace

UncertaintyCheck::UncertaintyCheck(const world::World& world, const UncertaintyCheckConfig& config)
    : world_(world), config_(config), caster_(world.mesh) {
  if (!(config.warmup > 0.0)) throw std::invalid_argument("u_check: warmup must be positive");
  if (config.trials < 1) throw std::invalid_argument("u_check: trials must be at least 1");
  if (!(config.start_rotation_sigma >= 0.0) || !(config.start_position_sigma >= 0.0)) {
    throw std::invalid_argument("u_check: the start perturbations must be non-negative");
  }
  config_.controller.mode = mpc::Mode::kUaMpc;
  config_.odometry.use_imu = false;
}

ProbeResult UncertaintyCheck::probe(double t) {
  const world::Trajectory& truth = world_.trajectory;
  const double frame = caster_.frameDuration();
  const double from = std::max(0.0, t - config_.warmup);
  if (t - from < 2.0 * frame || t + 2.0 * frame > truth.endTime()) {
    throw std::invalid_argument("u_check: probe time " + std::to_string(t) +
                                " s leaves no warm-up or lies past the path's end (" + std::to_string(truth.endTime()) +
                                " s)");
  }

  // 1. The LO up to t, motor at constant speed.
  const frames::MotorAngleTrack spinning = constantSpeedMotor(config_.motor_speed, from - 1.0, t + 1.0);
  lo::OdometryConfig odometry_config = config_.odometry;
  std::uint64_t k = static_cast<std::uint64_t>(std::ceil(from / frame));
  lo::MotorizedLidarOdometry odometry;
  lo::OdometryResult last;
  for (; (k + 1) * frame <= t; ++k) {
    const lo::Scan scan = toOdometryScan(caster_.castFrame(k, k * frame, truth, spinning));
    if (!odometry.initialised()) {
      startAtTruth(odometry_config, truth, scanEndTime(scan));
      odometry = lo::MotorizedLidarOdometry(odometry_config);
    }
    last = odometry.registerScan(scan, spinning);
  }
  ProbeResult result;
  result.time = last.time;
  const Eigen::Isometry3d T_true = truth.poseAt(last.time);
  result.lo_position_error = (T_true.translation() - last.T_WB.translation()).norm();
  result.lo_rotation_error = rotationAngle(T_true.linear().transpose() * last.T_WB.linear());
  constexpr double kMangledRotation = 5.0 * M_PI / 180.0;
  result.lo_lost = last.lost || result.lo_rotation_error > kMangledRotation;

  // 2. U as the controller computes it, from the LO's pose and local map.
  std::vector<Eigen::Vector3f> map_points;  // float32, as the LO publishes it and the mpc component holds it
  odometry.localMap().pointsSince(last.time - config_.local_map_window, map_points);
  result.local_map_points = map_points.size();
  mpc::UaMpcController controller(config_.controller);
  const mpc::UaMpcController::Decision decision = controller.stepFloat(last.T_WB, map_points, 0.0);

  // 3. Each angle's static view registered by the LO's update, from its prediction.
  const lo::UpdateOptions options = lo::updateOptionsFrom(config_.odometry);
  const mpc::UncertaintyModel criterion(config_.controller.uncertainty);
  world::SeededRandom random(world::mixSeed(config_.seed, k));
  for (std::size_t s = 0; s < decision.samples.size(); ++s) {
    AngleCheck check;
    check.theta = decision.sample_start + double(s) * decision.sample_step;
    check.predicted = decision.samples[s];
    const frames::MotorAngleTrack held = constantSpeedMotor(0.0, k * frame - 1.0, (k + 1) * frame + 1.0, check.theta);
    const lo::Scan scan = toOdometryScan(caster_.castFrame(k, k * frame, truth, held));
    const lo::DerotatedScan derotated =
        lo::derotate(scan, held, config_.odometry.calibration, config_.odometry.min_range, config_.odometry.max_range);
    const std::vector<lo::TimedPoint> keypoints =
        lo::voxelDownsample(derotated.points, config_.odometry.scan_voxel_size);
    lo::IteratedEkf predicted(stateOf(last), last.covariance);
    predicted.predict(derotated.end_time - last.time, config_.odometry.linear_process_noise,
                      config_.odometry.angular_process_noise);

    lo::IteratedEkf unperturbed = predicted;
    const lo::UpdateSummary summary = unperturbed.update(keypoints, odometry.localMap(), options);
    check.correspondences = summary.correspondences;
    check.oracle = criterion.aOptimality(summary.pose_information);
    check.posterior_trace = unperturbed.covariance().topLeftCorner<6, 6>().trace();

    // Against the unperturbed registration, not ground truth: the map is the LO's, drifted with
    // it (19 m along a plain corridor's axis after 30 s), and a registration can at best land
    // where that map puts the scan. What is measured is how much of a wrong start it removes.
    const lo::BaseState& reference = unperturbed.state();
    double sum_rotation = 0.0, sum_position = 0.0;
    for (int trial = 0; trial < config_.trials; ++trial) {
      lo::BaseState start = predicted.state();
      const Eigen::Vector3d dphi(random.normal(), random.normal(), random.normal());
      const Eigen::Vector3d dr(random.normal(), random.normal(), random.normal());
      start.R_WB = start.R_WB * lo::expSO3(config_.start_rotation_sigma * dphi);
      start.r_WB += config_.start_position_sigma * dr;
      lo::IteratedEkf perturbed(start, predicted.covariance());
      perturbed.update(keypoints, odometry.localMap(), options);
      const double rotation = rotationAngle(reference.R_WB.transpose() * perturbed.state().R_WB);
      const double position = (reference.r_WB - perturbed.state().r_WB).norm();
      sum_rotation += rotation * rotation;
      sum_position += position * position;
    }
    check.rms_rotation = std::sqrt(sum_rotation / config_.trials);
    check.rms_position = std::sqrt(sum_position / config_.trials);
    check.mean_square_error = (sum_rotation + sum_position) / config_.trials;
    result.angles.push_back(check);
  }

  // 4. Rank agreement over the angles.
  std::vector<double> predicted, oracle, trace, error;
  for (const AngleCheck& a : result.angles) {
    predicted.push_back(a.predicted);
    oracle.push_back(a.oracle);
    trace.push_back(a.posterior_trace);
    error.push_back(a.mean_square_error);
  }
  result.spearman_trace = app::spearman(predicted, trace);
  result.spearman_error = app::spearman(predicted, error);
  result.spearman_oracle_trace = app::spearman(oracle, trace);
  result.spearman_oracle_error = app::spearman(oracle, error);
  return result;
}

}  // namespace uampc::tools
