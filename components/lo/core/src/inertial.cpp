#include "uampc/lo/inertial.hpp"

#include <cmath>

namespace uampc::lo {

namespace {

// A reading is held at most this long (10 readings at 200 Hz): a longer gap means the IMU stopped,
// and the caller falls back to the constant-velocity model rather than extrapolate one reading.
constexpr double kMaxHold = 0.05;  // s

// One reading in B (see the header for the formulas).
InertialStep toBase(const ImuReading& reading, double theta, double theta_dot, double theta_ddot,
                    const frames::MotorLidarCalibration& calibration) {
  const Eigen::Isometry3d T_BL = frames::lidarPoseInBase(theta, calibration);
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();
  InertialStep step;
  step.angular_velocity_B = T_BL.linear() * reading.angular_velocity_L - theta_dot * e_z;
  const Eigen::Vector3d& w = step.angular_velocity_B;
  const Eigen::Vector3d t = T_BL * calibration.imu_position_L;  // the IMU's origin in B
  const Eigen::Vector3d t_dot = theta_dot * e_z.cross(t);
  const Eigen::Vector3d t_ddot = theta_dot * theta_dot * e_z.cross(e_z.cross(t)) + theta_ddot * e_z.cross(t);
  step.specific_force_B =
      T_BL.linear() * reading.specific_force_L - (t_ddot + 2.0 * w.cross(t_dot) + w.cross(w.cross(t)));
  return step;
}

// The motor's angular acceleration at t, rad/s^2, given its rate there: the rate's central
// difference over kAccelerationStep, one-sided at the track's ends, 0 where the track holds one
// rate only.
constexpr double kAccelerationStep = 5e-3;  // s, one encoder interval at 200 Hz
double motorAcceleration(const frames::MotorAngleTrack& motor, double t, double rate_at_t) {
  const std::optional<double> before = motor.omegaAt(t - kAccelerationStep);
  const std::optional<double> after = motor.omegaAt(t + kAccelerationStep);
  if (before && after) return (*after - *before) / (2.0 * kAccelerationStep);
  if (after) return (*after - rate_at_t) / kAccelerationStep;
  if (before) return (rate_at_t - *before) / kAccelerationStep;
  return 0.0;
}

}  // namespace

bool usableImuReading(const ImuReading& reading, double newest_time) {
  return std::isfinite(reading.time) && reading.angular_velocity_L.allFinite() &&
         reading.specific_force_L.allFinite() && reading.time > newest_time;
}

std::vector<InertialStep> inertialSteps(const std::deque<ImuReading>& readings, double t0, double t1,
                                        const frames::MotorAngleTrack& motor,
                                        const frames::MotorLidarCalibration& calibration) {
  std::vector<InertialStep> steps;
  double covered_until = t0;
  for (std::size_t i = 0; i < readings.size() && covered_until < t1; ++i) {
    const ImuReading& reading = readings[i];
    if (reading.time <= t0) continue;
    const std::optional<double> theta = motor.thetaAt(reading.time);
    const std::optional<double> theta_dot = motor.omegaAt(reading.time);
    if (!theta || !theta_dot) return {};
    const double theta_ddot = motorAcceleration(motor, reading.time, *theta_dot);
    const double next = i + 1 < readings.size() ? readings[i + 1].time : t1;
    const double until = std::min(t1, std::max(next, reading.time));
    if (reading.time - covered_until > kMaxHold || until - reading.time > kMaxHold) return {};
    InertialStep step = toBase(reading, *theta, *theta_dot, theta_ddot, calibration);
    step.dt = until - covered_until;
    if (step.dt > 0.0) steps.push_back(step);
    covered_until = until;
  }
  if (steps.empty() || covered_until < t1) return {};
  return steps;
}

}  // namespace uampc::lo
