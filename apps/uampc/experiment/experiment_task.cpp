#include "experiment/experiment_task.hpp"

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>

#include "experiment/backends/experiment_runner.hpp"
#include "experiment/experiment_command.hpp"
#include "experiment/experiment_snapshot.hpp"
#include "experiment/file_lock.hpp"
#include "experiment/run_attempt.hpp"
#include "uampc/runtime/domain_run_lock.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace uampc::app {

namespace {

// A DDS domain of this node held by an exclusive lock on a file of the host's lock directory (the
// launcher's lock, domain_run_lock.hpp, on a file of its own); released on destruction or when the
// process dies.
class DomainClaim {
 public:
  // The first domain from `first` to kHighestDomainId nobody on this node holds; nullopt if none.
  // Throws LockFileError when a claim file cannot be used safely.
  static std::optional<DomainClaim> takeFirstFree(int first) {
    for (int domain = first; domain <= kHighestDomainId; ++domain) {
      auto lock = DomainRunLock::takeFile(DomainRunLock::kDirectory, "dds-domain-" + std::to_string(domain) + ".lock",
                                          "", nullptr);
      if (lock) return DomainClaim(domain, std::move(*lock));
    }
    return std::nullopt;
  }
  int domain() const { return domain_; }

 private:
  DomainClaim(int domain, DomainRunLock lock) : domain_(domain), lock_(std::move(lock)) {}
  int domain_;
  DomainRunLock lock_;
};

// Waits for the run, passing a stop request on to it once (the launcher then stops cleanly).
int waitForRun(ChildProcesses& children) {
  bool passed_on = false;
  while (true) {
    if (stopRequested() && !passed_on) {
      children.signalAll(SIGINT);
      passed_on = true;
    }
    if (const auto exit = children.waitForExit(Clock::now() + std::chrono::milliseconds(200))) return exit->status;
  }
}

}  // namespace

int experimentTaskCommand(const std::string& output_directory, long task_index, int domain_base) {
  const std::string prefix = "uampc experiment --run-task " + std::to_string(task_index) + ": ";
  ExperimentSnapshot snapshot;
  try {
    snapshot = readExperimentSnapshot(output_directory);
  } catch (const ExperimentError& e) {
    for (const auto& m : e.messages()) std::cerr << prefix << m << "\n";
    return 2;
  }
  if (task_index < 0 || static_cast<std::size_t>(task_index) >= snapshot.plan.size()) {
    std::cerr << prefix << "no such run: " << output_directory << "/" << kExperimentSnapshotFile << " plans runs 0 to "
              << snapshot.plan.size() - 1 << "\n";
    return 2;
  }
  const auto index = static_cast<std::size_t>(task_index);
  const PlannedRun& run = snapshot.plan[index];
  const std::string directory = (fs::path(output_directory) / run.directory).string();
  if (isRunComplete(directory, run.end)) {
    std::cerr << prefix << run.directory << " finished before; nothing to do\n";
    return 0;
  }
  std::optional<DomainClaim> claim;
  try {
    if (auto free = DomainClaim::takeFirstFree(domain_base)) claim.emplace(std::move(*free));
  } catch (const LockFileError& e) {
    std::cerr << prefix << printableText(e.what()) << "; the run was not started\n";
    return 1;
  }
  if (!claim) {
    std::cerr << prefix << "every DDS domain from " << domain_base << " to " << kHighestDomainId
              << " is held by another task on " << hostName() << "\n";
    return 3;
  }
  catchStopSignals();
  std::optional<FileLock> attempt;
  try {
    AttemptStart begun = beginAttempt(output_directory, index, run,
                                      thisProcess() + " (uampc experiment --run-task " + std::to_string(index) + ")");
    if (!begun.held_by.empty()) {
      std::cerr << prefix << run.directory << " is being run by " << begun.held_by << "; left alone\n";
      return 4;
    }
    if (!begun.error.empty()) {
      std::cerr << prefix << begun.error << "\n";
      return 1;
    }
    attempt = std::move(begun.lock);
  } catch (const fs::filesystem_error& e) {
    std::cerr << prefix << "cannot prepare its directory: " << e.what() << "\n";
    return 1;
  }
  std::cerr << prefix << run.directory << " on " << hostName() << ", DDS domain " << claim->domain() << "\n";
  ChildProcesses children;
  const auto start = Clock::now();
  try {
    startRun(children, "/proc/self/exe", run, directory, claim->domain());
  } catch (const std::exception& e) {
    std::cerr << prefix << "cannot start the run: " << e.what() << "\n";
    return 1;
  }
  const int status = waitForRun(children);
  RunResult result;
  const std::string error = recordRunEnd(directory, status, std::chrono::duration<double>(Clock::now() - start).count(),
                                         stopRequested(), run.end, result);
  std::cerr << prefix << run.directory << " " << statusName(result.status)
            << (result.failure.empty() ? "" : " (" + result.failure + ")") << "\n";
  if (!error.empty()) {
    std::cerr << prefix << error << "\n";
    return 1;
  }
  if (result.status == RunStatus::kNotRun) return 130;
  return result.status == RunStatus::kOk ? 0 : 1;
}

}  // namespace uampc::app
