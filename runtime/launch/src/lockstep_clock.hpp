// The lockstep clock (docs/dev/architecture.md section 3): publishes sim time on /clock and
// advances only when every process of the scene has acknowledged the current step.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
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

// Who steps the scene: this clock, ticking every process, or the processes themselves
// (Scene::processesStepThemselves(); `run-process --own-clock`), whose acknowledgements this side
// then only follows, for progress, hangs and the end of the run.
enum class ClockHost { kHere, kInTheProcess };

// check_processes is called while waiting; a non-empty answer (e.g. "process 'sim' died") stops
// the run with that error.
ClockResult runLockstepClock(const Scene& scene, const std::atomic<bool>& stop,
                             const std::function<std::string()>& check_processes, ClockHost host = ClockHost::kHere);

// clock.real_time_factor: sleeps until sim time `t` is due at `factor` times real time from
// `wall_start` (in slices, so that a stop is heard during a long pause); false if stopped.
bool paceTo(std::chrono::steady_clock::time_point wall_start, Time t, double factor, const std::atomic<bool>& stop);

// The last lockstep step of a run of `clock.duration` (steps are 0, 1, ... while their time is
// within it); -1 for a run without end.
std::int64_t lastStep(const ClockSettings& clock);

// Two runs on one domain: the side that notices the other first stays on the bus a moment (1.5 s)
// before it leaves. Discovery is not symmetric in time; without the pause a busy machine can let
// the noticing run tear down before the other has matched its writers, and the other then runs
// on alone, never naming the cause (seen in CI under AddressSanitizer).
void stayUntilTheOtherRunNotices();

// What a run says when another lockstep run shares its domain; evidence: what gave it away.
std::string anotherRunOnTheDomain(int domain_id, const std::string& evidence);

}  // namespace uampc
