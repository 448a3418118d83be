#include "uampc/frames/motorized_lidar.hpp"

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
