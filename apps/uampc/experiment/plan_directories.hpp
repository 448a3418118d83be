// A plan's run directories lie inside DIR/runs/ (docs/decisions/experiment-plan-inside-out.md).
// An attempt at a run empties its directory, so a plan entry naming "../x", an absolute path, or a
// path that a symbolic link leads out of DIR would have it remove what is not the experiment's
// (DIR/experiment.json is read from disk by --run-task and --collect: anyone who can write it
// decides). Each directory is normalised lexically and then, as far as it exists, resolved
// (weakly_canonical: symbolic links followed); both must lie strictly inside DIR/runs, DIR
// resolved the same way. No two entries may share a directory or hold one another's.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "experiment/backends/experiment_runner.hpp"

namespace uampc::app {

// "" or why plan entry `index`'s directory `relative` is not inside, naming the entry and the
// path it leads to: "plan entry 3 (../x): /data/x is not inside /data/out/runs".
std::string runDirectoryProblem(const std::string& output_directory, std::size_t index, const std::string& relative);

// The first problem of a plan's directories; "" when there is none.
std::string planDirectoriesProblem(const std::string& output_directory, const std::vector<PlannedRun>& plan);

}  // namespace uampc::app
