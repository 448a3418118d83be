// `uampc components` and `uampc validate`.
#pragma once

#include "cli/command_set.hpp"

#include "uampc/runtime/launcher.hpp"

namespace uampc::app {

enum class ComponentListFormat { kText, kJson, kMarkdown };

int componentsCommand(ComponentListFormat format);
int validateCommand(const LaunchOptions& options);

// `uampc components` and its options.
void addComponentsCommand(CommandSet& commands);

}  // namespace uampc::app
