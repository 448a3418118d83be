#include "uampc/frames/motorized_lidar.hpp"

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

Eigen::Matrix3d motorRotation(double theta) {
  return Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Vector3d lidarToBase(const Eigen::Vector3d& p_L, double theta,
                            const MotorLidarCalibration& calibration) {
  return motorRotation(theta) * (calibration.R_ML * p_L + calibration.r_ML);
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
