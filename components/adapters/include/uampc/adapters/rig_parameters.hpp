// The motorized-LiDAR rig as component parameters, declared and read in one place, so that the
// raycaster, lo, mpc and evaluator of a scene describe the same rig the same way.
#pragma once

#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc::adapters {

// Declares tilt_deg (LiDAR tilt about its own x axis on the motor, 30 by default as the reference
// rig) and lidar_offset (r_ML, m).
void declareRigParameters(ComponentSpec& spec);

// The LiDAR-to-motor calibration from those parameters; throws if lidar_offset is not 3 values.
frames::MotorLidarCalibration rigCalibration(const Context& ctx);

// A double-list parameter that must hold x, y, z; throws naming the parameter otherwise.
Eigen::Vector3d vector3Param(const Context& ctx, const std::string& name);

}  // namespace uampc::adapters
