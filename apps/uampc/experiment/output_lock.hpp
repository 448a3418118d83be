// The --out lock: one command drives an experiment's output directory at a time
// (docs/decisions/experiment-output-lock.md). The local runner, the Slurm backend's submitting
// (and watching, and collecting) command, --collect and --plan-only hold DIR/experiment.lock for
// as long as they run; a second one is refused, naming the first's pid and host. `--run-task`
// does not take it (its submitting command may hold it while it watches, and the tasks of one
// job run side by side): each task holds its own run instead (run_attempt.hpp), as every attempt
// at a run does.
#pragma once

#include <optional>
#include <string>

#include "experiment/file_lock.hpp"

namespace uampc::app {

inline constexpr char kOutputLockFile[] = "experiment.lock";

// Takes DIR/experiment.lock for `command` (what the holder text says this process is, e.g.
// "uampc experiment paper.yaml"). nullopt after saying why on stderr: another command holds it,
// or the file is not a lock file of its own; the command then exits 2.
std::optional<FileLock> lockOutputDirectory(const std::string& output_directory, const std::string& command);

}  // namespace uampc::app
