// The controller's parameters bound to the core's config (ParameterBinding), once: the mpc
// component declares and reads them from a scene, and the development tools apply
// `--set controller.NAME=VALUE` with them.
#pragma once

#include "uampc/mpc/ua_mpc_controller.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

void bindMpcParameters(ParameterBinding& b, mpc::UaMpcController::Config& c);

}  // namespace uampc
