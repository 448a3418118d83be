// Frames of a motorized LiDAR, in one place (docs/dev/architecture.md section 1, Eq. 1).
//
//   W: world (map) frame.   B: base frame, the body whose pose the LO estimates.
//   M: motor frame, rotated about the base z axis by the encoder angle theta.
//   L: LiDAR frame, fixed on the motor by the calibration (R_ML, r_ML).
//
//   p_W = R_WB(t) * ( R_BM(theta(t)) * ( R_ML * p_L + r_ML ) ) + r_WB(t)          (Eq. 1)
#pragma once

#include <Eigen/Geometry>

namespace uampc::frames {

// LiDAR-to-motor calibration: p_M = R_ML * p_L + r_ML.
struct MotorLidarCalibration {
  Eigen::Matrix3d R_ML = Eigen::Matrix3d::Identity();
  Eigen::Vector3d r_ML = Eigen::Vector3d::Zero();

  // The reference rig: the LiDAR tilted about its own x axis by tilt_rad (30 degrees there).
  static MotorLidarCalibration tiltedAboutX(double tilt_rad,
                                            const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());
  // Same tilt as the reference rig: 30 degrees about the LiDAR x axis.
  static MotorLidarCalibration referenceRig();
};

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
