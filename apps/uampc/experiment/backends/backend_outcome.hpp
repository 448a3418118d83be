// What a backend (here, or Slurm) hands back to `uampc experiment`: the runs' results when it has
// them, or the exit code it ends with when it has none (refused, interrupted, not waiting). The
// command alone writes results.md, results.json and the report from them.
#pragma once

#include <optional>
#include <vector>

#include "experiment/run_results.hpp"

namespace uampc::app {

struct BackendOutcome {
  std::optional<std::vector<RunResult>> results;  // none: nothing to write
  int exit_code = 0;                              // without results: the command's exit code
  bool interrupted = false;                       // Ctrl-C while the runs ran: exit 130 after writing
};

}  // namespace uampc::app
