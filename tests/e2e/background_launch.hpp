// `uampc launch` started in the background, for tests that signal or kill it while it runs.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace uampc::test {

// `uampc launch ARGS` in a process group of its own, as a shell starts a command, with stdout and
// stderr to `log`; `environment` is put before the command (NAME=VALUE ...).
pid_t startLaunch(const std::string& args, const std::string& log, const std::string& environment = "");
// The same for any command: `uampc ARGS`.
pid_t startUampc(const std::string& args, const std::string& log, const std::string& environment = "");

// Kills the process group of a command started above if it still runs when the guard goes out of
// scope: a test that stops half-way at a failed ASSERT leaves no viewer holding its port, nor a run
// its domain, for the test's retry or the next test.
class KilledIfStillRunning {
 public:
  explicit KilledIfStillRunning(pid_t pid) : pid_(pid) {}
  KilledIfStillRunning(const KilledIfStillRunning&) = delete;
  KilledIfStillRunning& operator=(const KilledIfStillRunning&) = delete;
  ~KilledIfStillRunning();

 private:
  pid_t pid_;
};

// Waits for condition, at most `limit` (a test that hangs is a failure, not a stall).
bool waitFor(const std::function<bool()>& condition, std::chrono::milliseconds limit);

// The launcher's exit code; -1 when it did not exit (or exited by a signal) within `limit`, after
// which its process group is killed.
int exitCodeOf(pid_t pid, std::chrono::seconds limit = std::chrono::seconds(30));

// The pids of a run's process groups (`uampc run-process ... --set domain_id=D`), optionally only
// the one named `process`. The domain tells runs of parallel tests apart.
std::vector<pid_t> processesOfRun(int domain, const std::string& process = "");

// Whether the file exists and contains `text`.
bool logHas(const std::string& log, const std::string& text);

}  // namespace uampc::test
