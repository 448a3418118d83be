// The lockstep clock (docs/design.md section 3): publishes sim time on /clock and advances only when
// every process of the scene has acknowledged the current step.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "uampc/runtime/scene.hpp"

namespace uampc {

struct ClockResult {
  bool ok = true;
  std::string error;       // why the run stopped early
  double sim_seconds = 0;  // sim time reached
  double wall_seconds = 0;     // of the loop, from the first step on
  double startup_seconds = 0;  // from the clock's start until every process was ready
};

// check_processes is called while waiting; a non-empty answer (e.g. "process 'sim' died") stops
// the run with that error.
ClockResult runLockstepClock(const Scene& scene, const std::atomic<bool>& stop,
                             const std::function<std::string()>& check_processes);

// Two runs on one domain: the side that notices the other first stays on the bus a moment (1.5 s)
// before it leaves. Discovery is not symmetric in time; without the pause a busy machine can let
// the noticing run tear down before the other has matched its writers, and the other then runs
// on alone, never naming the cause (seen in CI under AddressSanitizer).
void stayUntilTheOtherRunNotices();

}  // namespace uampc
