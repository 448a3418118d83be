// Gravity in the world frame W (z up), for the IMU the simulator makes and the LO integrates: one
// value for both, so that a simulated IMU at rest reads exactly what the LO expects.
#pragma once

#include <Eigen/Core>

namespace uampc::frames {

constexpr double kGravity = 9.81;  // m/s^2

inline Eigen::Vector3d gravityInWorld() { return Eigen::Vector3d(0.0, 0.0, -kGravity); }

}  // namespace uampc::frames
