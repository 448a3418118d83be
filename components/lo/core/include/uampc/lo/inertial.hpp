// LiDAR-inertial mode: an IMU fixed in the LiDAR frame L (the Livox Mid-360's), turning with the
// motor, replaces the constant-velocity prediction of the filter.
//
// A reading gives, in L, the angular velocity of L and the specific force at the IMU's origin. The base
// frame B is what the filter estimates, so the motor is taken out with the encoder (Eq. 1
// differentiated). With t = T_BL(theta) p_L the IMU's origin in B (p_L the rig's imu_offset: the
// IMU's origin in L, whose axes it shares) and the motor turning about the base z axis e_z:
//   omega_L = R_LB (omega_B + theta_dot e_z)
//       =>  omega_B = R_BL omega_L - theta_dot e_z
//   a_I = a_B + R_WB (t'' + 2 omega_B x t' + omega_B x (omega_B x t))      (alpha_B x t left out)
//       =>  f_B = R_BW (a_B - g) = R_BL f_L - (t'' + 2 omega_B x t' + omega_B x (omega_B x t))
// with t' = theta_dot e_z x t and t'' = theta_dot^2 e_z x (e_z x t) + theta_ddot e_z x t (the
// motor's acceleration from the encoder's rates). On the reference rig, with the LiDAR on the motor
// axis (r_ML = 0) and the IMU at its origin, the lever-arm terms vanish; an IMU 5 cm off the axis
// (the Mid-360's is up to that) feels theta_dot^2 |t| = 0.65 m/s^2 at 3.6 rad/s.
//
// Beyond the paper (its LO is LiDAR-only); not in the paper's protocol.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"

namespace uampc::lo {

// One IMU reading, LiDAR frame.
struct ImuReading {
  double time = 0.0;                                             // s
  Eigen::Vector3d angular_velocity_L = Eigen::Vector3d::Zero();  // rad/s
  Eigen::Vector3d specific_force_L = Eigen::Vector3d::Zero();    // m/s^2, gravity included
};

// Whether a reading can be used after one taken at newest_time: finite values and time, and
// newer. A reading that fails is refused, never integrated.
bool usableImuReading(const ImuReading& reading, double newest_time);

// A piece of the base's motion over dt: its angular velocity and the specific force at its
// origin, both in B, held constant over the piece.
struct InertialStep {
  double dt = 0.0;  // s
  Eigen::Vector3d angular_velocity_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d specific_force_B = Eigen::Vector3d::Zero();
};

// The readings in B, as steps covering (t0, t1] exactly: each reading holds from its own time to
// the next reading's (the first one also back to t0, the last one on to t1). Empty when a reading
// would be held longer than 50 ms (the IMU stopped) or the encoder does not cover a reading.
std::vector<InertialStep> inertialSteps(const std::deque<ImuReading>& readings, double t0, double t1,
                                        const frames::MotorAngleTrack& motor,
                                        const frames::MotorLidarCalibration& calibration);

// White-noise densities of the IMU (the Mid-360's ICM-40609 by default, as the simulator's).
struct InertialNoise {
  double gyro_noise_density = 7.85e-5;   // rad/s/sqrt(Hz)
  double accel_noise_density = 9.81e-4;  // m/s^2/sqrt(Hz)
  // The filter deskews a frame with one angular velocity, the frame's mean rate from the gyro;
  // what that misses of a changing rate is this variance, (rad/s)^2.
  double rate_variance = 1e-4;
};

}  // namespace uampc::lo
