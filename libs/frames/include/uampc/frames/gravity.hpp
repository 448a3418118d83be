// Gravity in the world frame W (z up), for the IMU the simulator makes and the LO integrates: one
// value for both, so that a simulated IMU at rest reads exactly what the LO expects.
#pragma once

#include <Eigen/Core>

namespace uampc::frames {

constexpr double kGravity = 9.81;  // m/s^2

// The unit g, in m/s^2: livox_ros_driver2 publishes the Mid-360's acceleration in it; the
// raycaster's livox layout divides by it and the LO multiplies by it (lo/acceleration_unit.hpp).
constexpr double kStandardGravity = 9.80665;

inline Eigen::Vector3d gravityInWorld() { return Eigen::Vector3d(0.0, 0.0, -kGravity); }

}  // namespace uampc::frames
