// Runs the components of one process group of a scene: loads them, binds their ports to DDS,
// and drives them from one thread, in lockstep with the clock or in real time.
#pragma once

#include <atomic>
#include <string>

#include "uampc/runtime/lockstep_topics.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc {

// Returns the process exit code: 0 after a clean stop, 1 when a component failed.
// Stops when `stop` becomes true (a signal handler sets it). own_clock: the process steps itself
// (Scene::processesStepThemselves(); every process of the scene must; the launcher then follows).
int runProcessGroup(const Scene& scene, const std::string& process, const std::string& output_directory,
                    const std::atomic<bool>& stop, bool own_clock = false);

}  // namespace uampc
