// A simulated IMU fixed in the LiDAR frame L, turning with the motor, as the Livox Mid-360's
// built-in IMU does.
//
// Sample k is taken at t_k = k / rate (sim time) and reports, in L,
//   angular velocity  omega_L = angular velocity of L relative to the world, expressed in L
//                               (the base's rotation and the motor's spin theta_dot together)
//   specific force    f_L     = R_WL^T (a_W - g_W),   g_W = (0, 0, -9.81) m/s^2
// where a_W is the acceleration of the IMU's origin, the rig's imu_offset in L (an origin off the
// motor axis adds the centripetal and tangential terms of the motor's turning), and
// T_WL(t) = T_WB(t) * lidarPoseInBase(theta(t)) (Eq. 1, frames/motorized_lidar.hpp); plus white
// noise and bias random walk (imu_noise.hpp). Samples depend only on (motion, seed, k).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>

#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/raycaster/imu_noise.hpp"

namespace uampc::raycaster {

// Where the IMU's motion comes from.
struct ImuMotion {
  std::function<Eigen::Isometry3d(double t)> base_pose_at;  // T_WB at t
  std::function<double(double t)> motor_angle_at;           // theta at t (rad): the encoder, as for the scans
  std::function<double(double t)> motor_rate_at;            // theta_dot at t (rad/s)
};

// The true (noise-free) readings.
struct ImuKinematics {
  Eigen::Vector3d angular_velocity;  // rad/s, omega_L
  Eigen::Vector3d specific_force;    // m/s^2, f_L
};

struct ImuSample {
  std::uint64_t index = 0;
  double time = 0.0;                    // s, t_k = index / rate
  Eigen::Vector3d angular_velocity;     // rad/s, in L, with noise
  Eigen::Vector3d linear_acceleration;  // m/s^2, specific force in L, with noise
};

struct ImuSimulatorConfig {
  frames::MotorLidarCalibration calibration = frames::MotorLidarCalibration::referenceRig();
  ImuNoiseParameters noise;
  double rate_hz = 200.0;  // the Mid-360's IMU rate
  std::uint64_t seed = 0;
  // s: the simulation's start; the bias random walk starts (at zero) at the first sample at or
  // after it (ImuNoise's origin). 0 in lockstep, the component's first wall-clock time in real time.
  double start_time = 0.0;
};

// Finite-difference steps (s), see imuKinematics().
constexpr double kImuRateStep = 1e-3;
constexpr double kImuAccelerationStep = 5e-3;
// A reading at t uses the motion over [t - kImuStencilHalfWidth, t + kImuStencilHalfWidth].
constexpr double kImuStencilHalfWidth = kImuAccelerationStep;

// omega_L and f_L at time t by central differences of the poses T_WL (see the .cpp for steps
// and errors).
ImuKinematics imuKinematics(double t, const ImuMotion& motion, const frames::MotorLidarCalibration& calibration);

class ImuSimulator {
 public:
  explicit ImuSimulator(ImuSimulatorConfig config);

  double sampleTime(std::uint64_t index) const { return static_cast<double>(index) / config_.rate_hz; }
  // The first sample index whose time is >= t (t >= 0).
  std::uint64_t firstIndexAtOrAfter(double t) const;

  // Sample `index`; the motion must be defined over its stencil (kImuStencilHalfWidth around
  // its time). Not const: the noise keeps the bias of the last index asked for.
  ImuSample sample(std::uint64_t index, const ImuMotion& motion);

  // Variance of one sample's white noise, per axis (for the message covariances).
  double gyroNoiseVariance() const { return noise_.gyroWhiteStddev() * noise_.gyroWhiteStddev(); }
  double accelNoiseVariance() const { return noise_.accelWhiteStddev() * noise_.accelWhiteStddev(); }

  const ImuSimulatorConfig& config() const { return config_; }

 private:
  ImuSimulatorConfig config_;
  ImuNoise noise_;
};

}  // namespace uampc::raycaster
