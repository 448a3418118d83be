#include "uampc/raycaster/imu_simulator.hpp"

#include <cmath>

#include "uampc/frames/gravity.hpp"

namespace uampc::raycaster {

namespace {

// log(R) as a rotation vector (axis * angle), accurate for the small angles it is used on.
Eigen::Vector3d rotationVector(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const double sin_half = q.vec().norm();
  if (sin_half < 1e-300) return Eigen::Vector3d::Zero();
  return 2.0 * std::atan2(sin_half, q.w()) / sin_half * q.vec();
}

}  // namespace

// Central differences of T_WL(u) = T_WB(u) * lidarPoseInBase(theta_local(u)) around t:
//
// - The motor angle: the encoder angle is quantised (12 bits: 1.5 mrad), and differentiating it
//   over the 5 ms between readings gives errors of up to 0.3 rad/s, or metres per second squared
//   on an origin off the motor axis. So around t the angle follows the encoder's rate instead,
//     theta_local(t + s) = theta(t) + theta_dot(t) s + theta_ddot(t) s^2 / 2,
//   theta_ddot from the rate at t +- h_a; at t itself it is the scans' angle.
// - omega_L = (log(R(t)^T R(t+h)) - log(R(t)^T R(t-h))) / (2h), h = 1 ms: both rotation vectors
//   are in L at t and their second-order terms cancel, so the error is O(h^2) (below 1e-6 rad/s
//   in the tests, with the base turning about an axis across the motor's). The 200 Hz ground
//   truth is interpolated by slerp: the base's rate is constant between its samples and blended
//   only within 1 ms of one.
// - a_W = (p(t+h_a) - 2 p(t) + p(t-h_a)) / h_a^2, h_a = 5 ms, p the origin of L. For the
//   linearly interpolated 200 Hz ground truth this is exactly the discrete second difference of
//   its samples, interpolated: the acceleration a piecewise-linear path holds at its knots,
//   spread over one period. Truncation error h_a^2 / 12 |p''''|: for an origin 0.1 m off the axis
//   at 7.2 rad/s, 0.1 * 7.2^4 * 25e-6 / 12 = 6e-4 m/s^2; rounding ~4 eps |p| / h_a^2, 4e-8 m/s^2
//   1 km from the origin.
ImuKinematics imuKinematics(double t, const ImuMotion& motion, const frames::MotorLidarCalibration& calibration) {
  const double h = kImuRateStep, h_a = kImuAccelerationStep;
  const double theta = motion.motor_angle_at(t);
  const double theta_dot = motion.motor_rate_at(t);
  const double theta_ddot = (motion.motor_rate_at(t + h_a) - motion.motor_rate_at(t - h_a)) / (2.0 * h_a);
  auto lidar_pose = [&](double u) {
    const double s = u - t;
    const double theta_local = theta + theta_dot * s + 0.5 * theta_ddot * s * s;
    return Eigen::Isometry3d(motion.base_pose_at(u) * frames::lidarPoseInBase(theta_local, calibration));
  };
  const Eigen::Isometry3d T_WL = lidar_pose(t);
  const Eigen::Matrix3d R_LW = T_WL.linear().transpose();

  ImuKinematics k;
  k.angular_velocity =
      (rotationVector(R_LW * lidar_pose(t + h).linear()) - rotationVector(R_LW * lidar_pose(t - h).linear())) /
      (2.0 * h);
  // The IMU's origin, off L's by the rig's imu_offset: it alone feels the lever arm's acceleration.
  const Eigen::Vector3d& p_L = calibration.imu_position_L;
  const Eigen::Vector3d a_W =
      (lidar_pose(t + h_a) * p_L - 2.0 * (T_WL * p_L) + lidar_pose(t - h_a) * p_L) / (h_a * h_a);
  k.specific_force = R_LW * (a_W - frames::gravityInWorld());
  return k;
}

ImuSimulator::ImuSimulator(ImuSimulatorConfig config)
    : config_(std::move(config)),
      noise_(config_.noise, config_.rate_hz, config_.seed,
             config_.rate_hz > 0.0 ? firstIndexAtOrAfter(config_.start_time) : 0) {}

std::uint64_t ImuSimulator::firstIndexAtOrAfter(double t) const {
  if (!(t > 0.0)) return 0;
  auto index = static_cast<std::uint64_t>(std::ceil(t * config_.rate_hz));
  // t * rate rounds: settle on the index against the sample times themselves.
  while (index > 0 && sampleTime(index - 1) >= t) --index;
  while (sampleTime(index) < t) ++index;
  return index;
}

ImuSample ImuSimulator::sample(std::uint64_t index, const ImuMotion& motion) {
  ImuSample s;
  s.index = index;
  s.time = sampleTime(index);
  const ImuKinematics truth = imuKinematics(s.time, motion, config_.calibration);
  const ImuErrors errors = noise_.at(index);
  s.angular_velocity = truth.angular_velocity + errors.gyro();
  s.linear_acceleration = truth.specific_force + errors.accel();
  return s;
}

}  // namespace uampc::raycaster
