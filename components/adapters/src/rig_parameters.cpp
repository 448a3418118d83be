#include "uampc/adapters/rig_parameters.hpp"

#include <cmath>
#include <stdexcept>

namespace uampc::adapters {

void declareRigParameters(ComponentSpec& spec) {
  spec.param("tilt_deg", 30.0, "LiDAR tilt about its own x axis on the motor, degrees (reference rig: 30)")
      .between(-180.0, 180.0);
  spec.param("lidar_offset", std::vector<double>{0.0, 0.0, 0.0}, "LiDAR origin in the motor frame (r_ML), m");
}

Eigen::Vector3d vector3Param(const Context& ctx, const std::string& name) {
  const auto v = ctx.paramDoubleList(name);
  if (v.size() != 3) throw std::runtime_error(name + " must have three values (x, y, z)");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

frames::MotorLidarCalibration rigCalibration(const Context& ctx) {
  return frames::MotorLidarCalibration::tiltedAboutX(ctx.paramDouble("tilt_deg") * M_PI / 180.0,
                                                     vector3Param(ctx, "lidar_offset"));
}

}  // namespace uampc::adapters
