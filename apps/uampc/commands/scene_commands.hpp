// `uampc launch | validate | graph | run-process | clock`: the commands that take a scene.
#pragma once

#include "cli/command_set.hpp"

namespace uampc::app {

void addSceneCommands(CommandSet& commands);

}  // namespace uampc::app
