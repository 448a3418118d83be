#include "experiment/run_attempt.hpp"

#include <filesystem>

#include "experiment/plan_directories.hpp"
#include "uampc/run_files/run_directory.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

// The markers first: should emptying stop half-way, no marker of before is left to be read.
void emptyRunDirectory(const fs::path& directory) {
  fs::remove(directory / run_files::kDoneMarker);
  fs::remove(directory / run_files::kFailedMarker);
  for (const auto& entry : fs::directory_iterator(directory)) {
    if (entry.path().filename() != kAttemptLockFile) fs::remove_all(entry.path());  // links, not their targets
  }
}

}  // namespace

AttemptStart beginAttempt(const std::string& output_directory, std::size_t index, const PlannedRun& run,
                          const std::string& holder_text) {
  AttemptStart start;
  start.error = runDirectoryProblem(output_directory, index, run.directory);
  if (!start.error.empty()) return start;
  const fs::path directory = fs::path(output_directory) / run.directory;
  fs::create_directories(directory);
  LockAttempt lock = lockFile((directory / kAttemptLockFile).string(), holder_text);
  start.held_by = std::move(lock.held_by);
  start.error = std::move(lock.error);
  if (!lock.lock) return start;
  emptyRunDirectory(directory);
  start.lock = std::move(lock.lock);
  return start;
}

bool holdsAnAttempt(const std::string& run_directory) {
  std::error_code error;
  for (fs::directory_iterator entry(run_directory, error), end; !error && entry != end; entry.increment(error)) {
    if (entry->path().filename() != kAttemptLockFile) return true;
  }
  return false;
}

}  // namespace uampc::app
