#include "uampc/frames/motorized_lidar.hpp"

#include <algorithm>
#include <cmath>

namespace uampc::frames {

MotorLidarCalibration MotorLidarCalibration::tiltedAboutX(double tilt_rad,
                                                          const Eigen::Vector3d& offset) {
  MotorLidarCalibration c;
  c.R_ML = Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
  c.r_ML = offset;
  return c;
}

MotorLidarCalibration MotorLidarCalibration::referenceRig() {
  constexpr double kThirtyDegrees = 30.0 * M_PI / 180.0;
  return tiltedAboutX(kThirtyDegrees);
}

MotorReading rotorReading(const MotorReading& encoder, const MotorLidarCalibration& calibration) {
  return {encoder.time - calibration.time_offset, encoder.theta - calibration.encoder_offset, encoder.omega};
}

Eigen::Matrix3d rotationFromRollPitchYaw(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d rollPitchYawFromRotation(const Eigen::Matrix3d& R) {
  // R = Rz Ry Rx: R(2,0) = -sin(pitch), R(2,1) / R(2,2) = tan(roll), R(1,0) / R(0,0) = tan(yaw).
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

MotorLidarCalibration withMountingError(const MotorLidarCalibration& believed, const MountingError& error) {
  // No error leaves the believed calibration untouched bit for bit (even a -0.0 stays one), so
  // that a scene without one renders exactly as before.
  MotorLidarCalibration truth = believed;
  if (!error.rotation_rpy.isZero(0.0)) truth.R_ML = believed.R_ML * rotationFromRollPitchYaw(error.rotation_rpy);
  if (!error.offset.isZero(0.0)) truth.r_ML = believed.r_ML + error.offset;
  if (error.encoder_offset != 0.0) truth.encoder_offset = believed.encoder_offset + error.encoder_offset;
  if (error.time_offset != 0.0) truth.time_offset = believed.time_offset + error.time_offset;
  return truth;
}

Eigen::Matrix3d motorRotation(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  Eigen::Matrix3d R;
  R << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return R;
}

Eigen::Vector3d lidarToBase(const Eigen::Vector3d& p_L, double theta,
                            const MotorLidarCalibration& calibration) {
  // R_BM(theta) turns about z only: four products instead of a 3x3 matrix (the LO runs this for
  // every point of every scan).
  const Eigen::Vector3d p_M = calibration.R_ML * p_L + calibration.r_ML;
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * p_M.x() - s * p_M.y(), s * p_M.x() + c * p_M.y(), p_M.z()};
}

Eigen::Isometry3d lidarPoseInBase(double theta, const MotorLidarCalibration& calibration) {
  const Eigen::Matrix3d R_BM = motorRotation(theta);
  Eigen::Isometry3d T_BL = Eigen::Isometry3d::Identity();
  T_BL.linear() = R_BM * calibration.R_ML;
  T_BL.translation() = R_BM * calibration.r_ML;
  return T_BL;
}

Eigen::Vector3d lidarToWorld(const Eigen::Vector3d& p_L, double theta,
                             const MotorLidarCalibration& calibration,
                             const Eigen::Isometry3d& T_WB) {
  return T_WB * lidarToBase(p_L, theta, calibration);
}

}  // namespace uampc::frames
