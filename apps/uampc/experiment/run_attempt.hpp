// An attempt at one run, by the local runner or by a --run-task: its directory checked to lie
// inside the output directory (plan_directories.hpp), then held by an exclusive lock on
// RUN_DIR/attempt.lock for as long as the attempt lasts, and only then emptied, markers first,
// so that no marker of an earlier attempt may pass for this one's. A run another attempt holds (an
// experiment on the same --out, a Slurm task, a Kubernetes pod) is left alone: no attempt clears a
// directory in flight (docs/decisions/experiment-output-lock.md).
#pragma once

#include <optional>
#include <string>

#include "experiment/backends/experiment_runner.hpp"
#include "experiment/file_lock.hpp"

namespace uampc::app {

inline constexpr char kAttemptLockFile[] = "attempt.lock";  // kept when the directory is emptied

struct AttemptStart {
  std::optional<FileLock> lock;  // held: the directory is this attempt's, emptied
  std::string held_by;           // another attempt holds the run: who ("pid 12 on node3 (...)")
  std::string error;             // the directory is outside, or its lock file is not one
};

// Begins an attempt at plan entry `index` in `output_directory`; `holder_text` says who this
// process is. Throws std::filesystem::filesystem_error naming the path when the directory cannot
// be made or emptied (a full disk, permissions): the runner stops on that.
AttemptStart beginAttempt(const std::string& output_directory, std::size_t index, const PlannedRun& run,
                          const std::string& holder_text);

// Whether the directory holds anything of an earlier attempt (its lock file aside).
bool holdsAnAttempt(const std::string& run_directory);

}  // namespace uampc::app
