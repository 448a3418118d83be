// `uampc launch`: validates a scene, starts one process per process group, runs the lockstep
// clock (or lets real time run), supervises the processes and stops everything cleanly.
#pragma once

#include <string>
#include <vector>

#include "uampc/runtime/scene.hpp"

namespace uampc {

struct LaunchOptions {
  std::string scene_path;
  std::vector<Override> overrides;
  std::string output_directory;  // empty: no output directory
};

// Exit codes: 0 success, 1 a process or component failed, 2 the scene is invalid, 130 Ctrl-C.
int launch(const LaunchOptions& options);

// `uampc run-process`: one process group of a scene. The launcher starts one per group; for runs
// spread over containers or hosts, start them by hand (see docker/compose.yaml).
int runProcessCommand(const LaunchOptions& options, const std::string& process);

// `uampc clock`: only the lockstep clock of a scene whose process groups run elsewhere.
int runClockCommand(const LaunchOptions& options);

}  // namespace uampc
