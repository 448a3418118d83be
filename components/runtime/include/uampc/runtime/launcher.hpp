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

// The hidden `uampc run-process` command a launcher starts for each process group.
int runProcessCommand(const LaunchOptions& options, const std::string& process);

}  // namespace uampc
