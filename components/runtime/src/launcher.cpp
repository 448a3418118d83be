#include "uampc/runtime/launcher.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <thread>

#include "lockstep_clock.hpp"
#include "uampc/runtime/child_processes.hpp"
#include "uampc/runtime/process_group.hpp"

namespace fs = std::filesystem;

namespace uampc {

namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

void onSignal(int signal) {
  g_signal = signal;
  g_stop = true;
}

void installSignalHandlers() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

std::string describeStatus(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  }
  return "status " + std::to_string(status);
}

Scene loadOrReport(const LaunchOptions& options, ComponentCatalog& catalog, bool& ok) {
  try {
    ok = true;
    return loadScene(options.scene_path, options.overrides, catalog);
  } catch (const SceneError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    std::cerr << "uampc: " << e.messages().size() << " error(s) in scene " << options.scene_path
              << "; nothing was started\n";
    ok = false;
    return {};
  }
}

// The child processes of a launch, one per process group.
class ProcessSupervisor {
 public:
  ProcessSupervisor(const Scene& scene, const LaunchOptions& options) : scene_(scene), options_(options) {}

  void start(const std::string& process) {
    ChildCommand command;
    command.name = process;
    command.executable = "/proc/self/exe";
    command.argv = {"uampc", "run-process", options_.scene_path, "--process", process};
    for (const auto& o : options_.overrides) {
      command.argv.push_back("--set");
      command.argv.push_back(o.text);
    }
    if (!options_.output_directory.empty()) {
      command.argv.push_back("--out");
      command.argv.push_back(options_.output_directory);
    }
    command.exec_failure_message = "uampc: exec of the process group '" + process + "' failed\n";
    children_.start(command);
  }

  // A process that ended since the last call, described; empty if none. Applies the restart
  // policy in real-time mode.
  std::string poll() {
    const auto exit = children_.pollExit();
    if (!exit) return {};
    const std::string& process = exit->name;
    if (g_stop && WIFEXITED(exit->status) && WEXITSTATUS(exit->status) == 0) return {};
    const std::string what =
        "process '" + process + "' (pid " + std::to_string(exit->pid) + ") " + describeStatus(exit->status);
    if (scene_.on_crash == CrashPolicy::kRestart && !g_stop && restarts_[process] < scene_.max_restarts) {
      ++restarts_[process];
      std::cerr << "uampc: " << what << "; restarting it (" << restarts_[process] << " of " << scene_.max_restarts
                << ")\n";
      start(process);
      return {};
    }
    failed_ = true;
    return what;
  }

  // Asks every process to stop, waits, and kills those that do not.
  void stopAll() {
    children_.signalAll(SIGTERM);
    const auto deadline = ChildProcesses::Clock::now() + std::chrono::seconds(5);
    while (!children_.empty()) {
      const auto exit = children_.waitForExit(deadline);
      if (!exit) {
        for (const auto& [pid, name] : children_.running())
          std::cerr << "uampc: process '" << name << "' did not stop within 5 s; killing it\n";
        children_.killAll();
        failed_ = true;
        break;
      }
      if (!(WIFEXITED(exit->status) && WEXITSTATUS(exit->status) == 0)) {
        std::cerr << "uampc: process '" << exit->name << "' " << describeStatus(exit->status) << " while stopping\n";
        failed_ = true;
      }
    }
  }

  bool empty() const { return children_.empty(); }
  bool failed() const { return failed_; }

 private:
  const Scene& scene_;
  const LaunchOptions& options_;
  ChildProcesses children_;
  std::map<std::string, int> restarts_;
  bool failed_ = false;
};

}  // namespace

int launch(const LaunchOptions& options) {
  ComponentCatalog catalog;
  bool ok = false;
  const Scene scene = loadOrReport(options, catalog, ok);
  // Only here, not in run-process and clock: launch starts those, and they would repeat them.
  for (const auto& w : scene.warnings) std::cerr << w << "\n";
  if (!ok) return 2;
  if (!options.output_directory.empty()) fs::create_directories(options.output_directory);

  installSignalHandlers();
  std::cerr << "uampc: scene '" << scene.name << "' (" << scene.components.size() << " components, "
            << scene.processes().size() << " process(es), "
            << (scene.clock.mode == ClockMode::kLockstep ? "lockstep" : "real time") << ", DDS domain "
            << scene.domain_id << ")\n";
  ProcessSupervisor supervisor(scene, options);
  for (const auto& process : scene.processes()) supervisor.start(process);

  std::string error;
  if (scene.clock.mode == ClockMode::kLockstep) {
    const ClockResult result = runLockstepClock(scene, g_stop, [&] { return supervisor.poll(); });
    if (!result.ok) error = result.error;
    std::cerr << "uampc: " << result.sim_seconds << " s of sim time in " << result.wall_seconds << " s ("
              << (result.wall_seconds > 0 ? result.sim_seconds / result.wall_seconds : 0.0) << "x real time)\n";
  } else {
    const auto start = std::chrono::steady_clock::now();
    while (!g_stop) {
      error = supervisor.poll();
      if (!error.empty() || supervisor.empty()) break;
      if (scene.clock.duration_s > 0 &&
          std::chrono::steady_clock::now() - start > std::chrono::duration<double>(scene.clock.duration_s)) {
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  supervisor.stopAll();
  if (!error.empty()) {
    std::cerr << "uampc: run failed: " << error << "\n";
    return 1;
  }
  if (supervisor.failed()) return 1;
  if (g_signal == SIGINT) {
    std::cerr << "uampc: stopped by Ctrl-C\n";
    return 130;
  }
  return 0;
}

int runClockCommand(const LaunchOptions& options) {
  installSignalHandlers();
  ComponentCatalog catalog;
  bool ok = false;
  const Scene scene = loadOrReport(options, catalog, ok);
  if (!ok) return 2;
  if (scene.clock.mode != ClockMode::kLockstep) {
    std::cerr << "uampc: scene " << options.scene_path << " runs in real time; it has no clock to run\n";
    return 2;
  }
  const ClockResult result = runLockstepClock(scene, g_stop, [] { return std::string(); });
  if (!result.ok) std::cerr << "uampc: run failed: " << result.error << "\n";
  return result.ok ? 0 : 1;
}

int runProcessCommand(const LaunchOptions& options, const std::string& process) {
  installSignalHandlers();
  ComponentCatalog catalog;
  bool ok = false;
  const Scene scene = loadOrReport(options, catalog, ok);
  if (!ok) return 2;
  bool known = false;
  for (const auto& p : scene.processes()) known = known || p == process;
  if (!known) {
    std::cerr << "uampc: the scene has no process '" << process << "'\n";
    return 2;
  }
  return runProcessGroup(scene, process, options.output_directory, g_stop);
}

}  // namespace uampc
