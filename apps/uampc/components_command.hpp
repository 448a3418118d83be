// `uampc components` and `uampc validate`.
#pragma once

#include "uampc/runtime/launcher.hpp"

namespace uampc::app {

int componentsCommand(bool json);
int validateCommand(const LaunchOptions& options);

}  // namespace uampc::app
