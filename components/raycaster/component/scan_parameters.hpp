// The simulated LiDAR's noise parameters bound to the core's config (ParameterBinding), once: the
// raycaster declares and reads them from a scene, and the development tools apply
// `--set lidar.NAME=VALUE` with them.
#pragma once

#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

// The core's config with a scene's defaults where they differ from the core's: range noise.
raycaster::RayCasterConfig sceneScanDefaults();

void bindScanParameters(ParameterBinding& b, raycaster::RayCasterConfig& c);

}  // namespace uampc
