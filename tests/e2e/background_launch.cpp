#include "background_launch.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <thread>

#include "command_runner.hpp"

namespace uampc::test {

pid_t startLaunch(const std::string& args, const std::string& log, const std::string& environment) {
  return startUampc("launch " + args, log, environment);
}

pid_t startUampc(const std::string& args, const std::string& log, const std::string& environment) {
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const std::string command = "exec env UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " + environment +
                                " " + binaryPath("bin/uampc") + " " + args + " > " + log + " 2>&1";
    execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);  // both sides: whichever runs first
  return pid;
}

KilledIfStillRunning::~KilledIfStillRunning() {
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) != 0) return;  // exited (or reaped by exitCodeOf) already
  kill(-pid_, SIGKILL);
  waitpid(pid_, &status, 0);
}

bool waitFor(const std::function<bool()>& condition, std::chrono::milliseconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

int exitCodeOf(pid_t pid, std::chrono::seconds limit) {
  int status = 0;
  const bool exited = waitFor([&] { return waitpid(pid, &status, WNOHANG) == pid; }, limit);
  if (!exited) {
    kill(-pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<pid_t> processesOfRun(int domain, const std::string& process) {
  // [u] keeps the shell that runs pgrep from matching its own command line.
  const std::string pattern = "[u]ampc run-process .*" + (process.empty() ? "" : "--process " + process + " .*") +
                              "domain_id=" + std::to_string(domain) + "( |$)";
  std::vector<pid_t> pids;
  std::istringstream lines(runShell("pgrep -f '" + pattern + "'").output);
  for (pid_t pid; lines >> pid;) pids.push_back(pid);
  return pids;
}

bool logHas(const std::string& log, const std::string& text) {
  return std::filesystem::exists(log) && readFile(log).find(text) != std::string::npos;
}

}  // namespace uampc::test
