// The world's and its trajectory's parameters bound to world::WorldSettings (ParameterBinding),
// once: map_provider declares and reads them from a scene, and the development tools apply
// `--set world.NAME=VALUE` with them.
#pragma once

#include "uampc/runtime/parameter_binding.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc {

void bindWorldParameters(ParameterBinding& b, world::WorldSettings& s);

}  // namespace uampc
