// `uampc components` and `uampc validate`.
#pragma once

#include "uampc/runtime/launcher.hpp"

namespace uampc::app {

enum class ComponentListFormat { kText, kJson, kMarkdown };

int componentsCommand(ComponentListFormat format);
int validateCommand(const LaunchOptions& options);

}  // namespace uampc::app
