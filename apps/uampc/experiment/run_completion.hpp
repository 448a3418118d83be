// When a run of an experiment counts as done (docs/decisions/experiment-run-done.md): `uampc
// launch` exited 0 (its done marker says so), no attempt marked it failed, and its metrics.json's
// sim time reached the scene's end, clock.duration, within one lockstep step. A launcher stopped
// by a signal may exit 0 and still write metrics.json, of the time it reached: those runs are cut
// short, not done. Resume, --collect, --run-task and the Slurm backend all ask here.
#pragma once

#include <string>

#include "experiment/run_results.hpp"

namespace uampc {
struct Scene;
}

namespace uampc::app {

// Where a planned run's simulated time ends (its scene with every override applied).
struct SceneEnd {
  double duration_s = 0.0;  // clock.duration
  double step_s = 0.0;      // clock.step: how far short of it the last step may end
};

// The scene's end. `problem` is set when an experiment could not tell when its runs are done: a
// scene that runs until Ctrl-C (duration 0), or in real time (its sim time is the wall clock).
SceneEnd sceneEndOf(const Scene& scene, std::string* problem);

bool reachesSceneEnd(double sim_time_s, const SceneEnd& end);
// "sim time 13.9 s of 20 s", for people.
std::string simTimeOfEnd(double sim_time_s, const SceneEnd& end);

enum class RunState {
  kDone,        // done marker, no failed marker, metrics that reach the scene's end
  kFailed,      // a failed marker, or a done marker its metrics do not bear out
  kUnfinished,  // neither marker: never run, running, or stopped before it ended
};

struct RunCompletion {
  RunState state = RunState::kUnfinished;
  std::string reason;  // why it is not done, for people; empty when done
};

// What a run directory says of its run.
RunCompletion runCompletion(const std::string& run_directory, const SceneEnd& end);
bool isRunComplete(const std::string& run_directory, const SceneEnd& end);

}  // namespace uampc::app
