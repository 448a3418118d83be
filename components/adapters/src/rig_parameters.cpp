#include "uampc/adapters/rig_parameters.hpp"

#include <cmath>
#include <stdexcept>

namespace uampc::adapters {

void declareRigParameters(ComponentSpec& spec) {
  spec.param("tilt_deg", 30.0, "LiDAR tilt about its own x axis on the motor, degrees (reference rig: 30)")
      .between(-180.0, 180.0);
  spec.param("lidar_offset", std::vector<double>{0.0, 0.0, 0.0}, "LiDAR origin in the motor frame (r_ML), m");
}

frames::MotorLidarCalibration rigCalibration(const Context& ctx) {
  const auto offset = ctx.paramDoubleList("lidar_offset");
  if (offset.size() != 3) throw std::runtime_error("lidar_offset must have three values (x, y, z)");
  return frames::MotorLidarCalibration::tiltedAboutX(ctx.paramDouble("tilt_deg") * M_PI / 180.0,
                                                     Eigen::Vector3d(offset[0], offset[1], offset[2]));
}

}  // namespace uampc::adapters
