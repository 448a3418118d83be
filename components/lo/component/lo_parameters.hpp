// The LO's parameters bound to the core's config (ParameterBinding), once: the component declares
// and reads them from a scene, and the development tools apply `--set lo.NAME=VALUE` with them.
#pragma once

#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

void bindLoParameters(ParameterBinding& b, lo::OdometryConfig& c);

}  // namespace uampc
