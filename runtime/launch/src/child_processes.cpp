#include "uampc/runtime/child_processes.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <thread>

extern char** environ;

namespace uampc {

namespace {

std::vector<char*> nullTerminated(std::vector<std::string>& texts) {
  std::vector<char*> pointers;
  for (auto& t : texts) pointers.push_back(t.data());
  pointers.push_back(nullptr);
  return pointers;
}

// waitpid for one child, retried when a signal interrupts it; -1 if the child is not ours to reap.
pid_t waitFor(pid_t pid, int& status, int options) {
  pid_t result;
  while ((result = waitpid(pid, &status, options)) < 0 && errno == EINTR) {
  }
  if (result < 0) status = -1;
  return result;
}

// In the child between fork and exec: only async-signal-safe calls (the parent may have threads,
// e.g. Fast DDS's, holding locks that malloc or stdio would wait for forever).
[[noreturn]] void execInChild(pid_t parent, const char* executable, char* const* argv, char* const* envp,
                              const char* log_file, const std::string& failure_message) {
  // A child stops when its parent dies, even by SIGKILL: SIGTERM asks it to stop as Ctrl-C would
  // (a lockstep process would otherwise wait for a clock that is gone, a real-time one would go on
  // commanding the motor). The parent may have died before prctl: then getppid() has changed.
  // (Sent when the thread that forked ends: ours are started from the main thread.)
  prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (getppid() != parent) _exit(128 + SIGTERM);
  if (log_file) {
    const int fd = open(log_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = open("/dev/null", O_RDONLY);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    if (null >= 0) dup2(null, STDIN_FILENO);
  }
  execve(executable, argv, envp);
  (void)!write(STDERR_FILENO, failure_message.data(), failure_message.size());
  _exit(127);
}

}  // namespace

pid_t ChildProcesses::start(const ChildCommand& command) {
  // Prepared before fork: the child may not allocate.
  std::vector<std::string> argv_text = command.argv;
  std::vector<std::string> environment;
  if (command.environment) {
    environment = *command.environment;
  } else {
    for (char** entry = environ; *entry; ++entry) environment.emplace_back(*entry);
  }
  const std::vector<char*> argv = nullTerminated(argv_text), envp = nullTerminated(environment);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::system_error(errno, std::generic_category(), "fork failed");
  if (pid == 0) {
    execInChild(parent, command.executable.c_str(), argv.data(), envp.data(),
                command.log_file.empty() ? nullptr : command.log_file.c_str(), command.exec_failure_message);
  }
  running_[pid] = command.name;
  return pid;
}

std::optional<ChildExit> ChildProcesses::pollExit() {
  for (auto it = running_.begin(); it != running_.end(); ++it) {
    int status = 0;
    if (waitFor(it->first, status, WNOHANG) == 0) continue;  // still running
    ChildExit exit{it->first, it->second, status};
    running_.erase(it);
    return exit;
  }
  return std::nullopt;
}

std::optional<ChildExit> ChildProcesses::waitForExit(Clock::time_point deadline) {
  while (true) {
    if (auto exit = pollExit()) return exit;
    if (running_.empty() || Clock::now() > deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void ChildProcesses::signalAll(int signal) const {
  for (const auto& [pid, name] : running_) kill(pid, signal);
}

std::vector<ChildExit> ChildProcesses::killAll() {
  signalAll(SIGKILL);
  std::vector<ChildExit> exits;
  for (const auto& [pid, name] : running_) {
    int status = 0;
    waitFor(pid, status, 0);
    exits.push_back({pid, name, status});
  }
  running_.clear();
  return exits;
}

std::string describeExitStatus(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  }
  return "status " + std::to_string(status);
}

}  // namespace uampc
