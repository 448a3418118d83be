// Frames of a motorized LiDAR, in one place (docs/dev/architecture.md section 1, Eq. 1).
//
//   W: world (map) frame.   B: base frame, the body whose pose the LO estimates.
//   M: motor frame, rotated about the base z axis by the encoder angle theta.
//   L: LiDAR frame, fixed on the motor by the calibration (R_ML, r_ML).
//
// theta(t) is the rotor's angle at the point's time on the LiDAR's clock. The encoder measures it
// with a zero of its own (encoder_offset) and on a clock of its own (time_offset); rotorReading
// below is the one place both are taken out (docs/decisions/rig-calibration-conventions.md).
//
//   p_W = R_WB(t) * ( R_BM(theta(t)) * ( R_ML * p_L + r_ML ) ) + r_WB(t)          (Eq. 1)
#pragma once

#include <Eigen/Geometry>

#include "uampc/frames/motor_angle_track.hpp"

namespace uampc::frames {

// The rig's calibration: the LiDAR on the rotor, p_M = R_ML * p_L + r_ML, and how the encoder's
// readings relate to Eq. 1's theta(t).
struct MotorLidarCalibration {
  Eigen::Matrix3d R_ML = Eigen::Matrix3d::Identity();
  Eigen::Vector3d r_ML = Eigen::Vector3d::Zero();
  // The encoder's zero, rad: the encoder reads theta_encoder = theta + encoder_offset.
  double encoder_offset = 0.0;
  // The LiDAR-to-encoder clock offset, s: a point stamped t on the LiDAR's clock was measured when
  // the encoder's clock read t + time_offset (its angle is the encoder's theta(t + time_offset)).
  double time_offset = 0.0;
  // The IMU's origin in the LiDAR frame L, m; its axes are L's (the Livox Mid-360's: 11.0, 23.29,
  // -44.12 mm). Only the LiDAR-inertial LO and the simulated IMU use it: the IMU turns with the
  // LiDAR, so a point off the motor axis feels the motor's centripetal acceleration.
  Eigen::Vector3d imu_position_L = Eigen::Vector3d::Zero();

  // The reference rig: the LiDAR tilted about its own x axis by tilt_rad (30 degrees there).
  static MotorLidarCalibration tiltedAboutX(double tilt_rad,
                                            const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());
  // Same tilt as the reference rig: 30 degrees about the LiDAR x axis.
  static MotorLidarCalibration referenceRig();
};

// An encoder reading as Eq. 1 needs it: the rotor's angle theta_encoder - encoder_offset, at the
// time on the LiDAR's clock, time - time_offset (the rate is unchanged). Zero offsets give the
// reading back bit for bit.
MotorReading rotorReading(const MotorReading& encoder, const MotorLidarCalibration& calibration);

// R = Rz(yaw) Ry(pitch) Rx(roll), rad: roll about x first, then pitch about the fixed y, then yaw
// about the fixed z (ROS's fixed-axis roll, pitch, yaw). rpy = (roll, pitch, yaw).
Eigen::Matrix3d rotationFromRollPitchYaw(const Eigen::Vector3d& rpy);
// The inverse, with pitch in [-pi/2, pi/2].
Eigen::Vector3d rollPitchYawFromRotation(const Eigen::Matrix3d& R);

// A mounting error of the rig: the true calibration is the believed one composed with it.
struct MountingError {
  Eigen::Vector3d rotation_rpy = Eigen::Vector3d::Zero();  // rad, in the LiDAR frame: R_ML R(rpy)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();        // m, in the motor frame: r_ML + offset
  double encoder_offset = 0.0;                             // rad, added to encoder_offset
  double time_offset = 0.0;                                // s, added to time_offset
};
MotorLidarCalibration withMountingError(const MotorLidarCalibration& believed, const MountingError& error);

// R_BM(theta): rotation about the base z axis by the encoder angle theta (rad).
Eigen::Matrix3d motorRotation(double theta);

// The inner bracket of Eq. 1: a LiDAR point expressed in the base frame at encoder angle theta.
Eigen::Vector3d lidarToBase(const Eigen::Vector3d& p_L, double theta,
                            const MotorLidarCalibration& calibration);

// Rotation and origin of the LiDAR frame in the base frame at encoder angle theta:
// R_BL = R_BM(theta) R_ML, t_BL = R_BM(theta) r_ML.
Eigen::Isometry3d lidarPoseInBase(double theta, const MotorLidarCalibration& calibration);

// Eq. 1 in full: a LiDAR point in the world frame, given the base pose T_WB at the point's time.
Eigen::Vector3d lidarToWorld(const Eigen::Vector3d& p_L, double theta,
                             const MotorLidarCalibration& calibration,
                             const Eigen::Isometry3d& T_WB);

}  // namespace uampc::frames
