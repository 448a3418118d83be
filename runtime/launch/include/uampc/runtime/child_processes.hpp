// The child processes a uampc command starts and supervises: the launcher's process groups and the
// experiment runner's runs. One place for fork/exec, reaping and stopping, so that both get the
// same care (nothing but async-signal-safe calls between fork and exec; only their own children
// reaped).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace uampc {

struct ChildCommand {
  std::string name;                                     // for messages: the process group, the run
  std::string executable;                               // a path, not searched in PATH
  std::vector<std::string> argv;                        // argv[0] included
  std::optional<std::vector<std::string>> environment;  // "NAME=value" entries; none: this process's
  std::string log_file;                                 // stdout and stderr to it (truncated), stdin from /dev/null;
                                                        // empty: the child shares this process's stdio
  std::string exec_failure_message;                     // written to the child's stderr if exec fails (exit code 127)
};

struct ChildExit {
  pid_t pid;
  std::string name;
  int status;  // as waitpid reports it; -1 if something else reaped the child (how it ended is unknown)
};

// Children started by start() until they are reaped by pollExit(), waitForExit() or killAll().
// Children still running when the pool is destroyed are left running (a run's launcher has
// children of its own that a kill would orphan): stop them first.
class ChildProcesses {
 public:
  using Clock = std::chrono::steady_clock;

  ChildProcesses() = default;
  ChildProcesses(const ChildProcesses&) = delete;
  ChildProcesses& operator=(const ChildProcesses&) = delete;

  // The child's pid. Throws std::system_error if fork fails; an exec failure shows as exit 127.
  pid_t start(const ChildCommand& command);

  // A child that ended, reaped; none if all are still running. Never blocks.
  std::optional<ChildExit> pollExit();
  // Like pollExit, but waits for an exit until the deadline.
  std::optional<ChildExit> waitForExit(Clock::time_point deadline);

  void signalAll(int signal) const;
  // SIGKILL to every child still running, each reaped.
  std::vector<ChildExit> killAll();

  bool empty() const { return running_.empty(); }
  std::size_t size() const { return running_.size(); }
  const std::map<pid_t, std::string>& running() const { return running_; }  // pid -> name

 private:
  std::map<pid_t, std::string> running_;
};

// How a child ended, from its waitpid status: "exited with status 1", "killed by signal 9 (Killed)".
std::string describeExitStatus(int status);

}  // namespace uampc
