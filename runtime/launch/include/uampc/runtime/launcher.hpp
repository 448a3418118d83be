// `uampc launch`: validates a scene, starts one process per process group, runs the lockstep
// clock (or lets real time run), supervises the processes and stops everything cleanly.
#pragma once

#include <string>
#include <vector>

#include "uampc/runtime/scene.hpp"
#include "uampc/runtime/viewer_process.hpp"

namespace uampc {

struct LaunchOptions {
  std::string scene_path;
  std::vector<Override> overrides;
  std::string output_directory;  // empty: no output directory
  // launch only: write into an output directory that already holds a run (--overwrite); without it
  // launch refuses one (docs/decisions/no-silent-overwrite.md).
  bool overwrite = false;
  ViewerOptions viewer;          // launch only: a live viewer beside the run (--view)
  // Recorded with the run (run_record.hpp); the uampc command fills them in from its version.
  std::string uampc_version = "unknown";
  std::string fastdds_version = "unknown";
};

// Exit codes: 0 success, 1 a process or component failed (or the run's record could not be
// written, or the output directory holds an earlier run and overwrite is false), 2 the scene is invalid, 130 Ctrl-C (SIGINT), whether the processes were still starting
// or already running. With an output directory, writes the run's record there before anything
// starts (run_record.hpp).
int launch(const LaunchOptions& options);

// `uampc run-process`: one process group of a scene. The launcher starts one per group; for runs
// spread over containers or hosts, start them by hand (see docker/compose.yaml). own_clock: the
// process steps itself (the launcher passes it for a scene of one process, clock.in_process).
int runProcessCommand(const LaunchOptions& options, const std::string& process, bool own_clock = false);

// `uampc clock`: only the lockstep clock of a scene whose process groups run elsewhere.
int runClockCommand(const LaunchOptions& options);

}  // namespace uampc
