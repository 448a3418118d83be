// Which of a process group's ports discovery has not matched yet (process_group.cpp waits for
// them before the run starts).
#pragma once

#include <string>

#include "uampc/runtime/scene.hpp"

namespace uampc::process {

struct ProcessState;

// The components' ports discovery has not matched yet: each writer's readers and each reader's
// writers as the scene counts them. One line each, empty when all are matched.
std::string unmatchedPorts(const Scene& scene, const ProcessState& state);

// What to add to a start that did not complete: for a secured scene, that Fast DDS 2.9 may never
// complete a DDS Security handshake (docs/user/security.md); empty otherwise.
std::string securedStartHint(const Scene& scene);

}  // namespace uampc::process
