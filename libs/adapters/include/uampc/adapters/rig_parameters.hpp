// The motorized-LiDAR rig as component parameters, declared and read in one place. They are
// marked partOfRig(): a scene sets them once in its rig: block and the loader gives the same value
// to the raycaster, lo, mpc and evaluator (docs/dev/architecture.md section 5). The motor axis is
// the base frame's z axis by definition (Eq. 1's R_BM(theta)); a rig mounted otherwise is described
// by where its base frame is, not by a parameter.
#pragma once

#include <map>
#include <string>

#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/lidar/lidar_model.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc::adapters {

// Declares the rig's calibration (docs/user/scenes.md, "The rig"): tilt_deg (LiDAR tilt about its
// own x axis on the motor, 30 by default as the reference rig) or lidar_rotation_rpy_deg (the
// whole R_ML), lidar_offset (r_ML, m), encoder_offset_deg and time_offset (their signs:
// docs/decisions/rig-calibration-conventions.md).
void declareRigParameters(ComponentSpec& spec);

// The rig's calibration from those parameters; throws if lidar_offset or lidar_rotation_rpy_deg
// (when given) is not 3 values.
frames::MotorLidarCalibration rigCalibration(const Context& ctx);
// The same from a scene's rig values (Scene::rig: what every component was given), the declared
// defaults for what it lacks: for tools that read a scene's rig without running it.
frames::MotorLidarCalibration rigCalibration(const std::map<std::string, ParameterValue>& rig);

// Declares lidar_model (livox_mid360 by default) and the lidar_* description of a model: spinning
// LiDAR (beam elevations, points per second, frame rate, ranges).
void declareLidarModelParameters(ComponentSpec& spec);

// The LiDAR model those parameters name.
lidar::LidarModel lidarModel(const Context& ctx);

// A double-list parameter that must hold x, y, z; throws naming the parameter otherwise.
Eigen::Vector3d vector3Param(const Context& ctx, const std::string& name);

// Each of three angles in degrees, in radians.
Eigen::Vector3d degreesToRadians(const Eigen::Vector3d& degrees);

}  // namespace uampc::adapters
