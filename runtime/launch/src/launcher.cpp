#include "uampc/runtime/launcher.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <thread>

#include "lockstep_clock.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/runtime/child_processes.hpp"
#include "uampc/runtime/domain_run_lock.hpp"
#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/process_group.hpp"
#include "uampc/runtime/run_record.hpp"
#include "uampc/runtime/shared_memory_cleanup.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace fs = std::filesystem;

namespace uampc {

namespace {

// How long the launcher waits for its processes to stop before it kills them. A process writes its
// outputs as it stops (the evaluator's metrics and figures): 5 s was too short on a machine loaded
// by other work (two of 55 complete runs of an experiment killed, while a compiler ran beside them).
constexpr std::chrono::seconds kStopWait{20};

// How a process ended when the user asked everything to stop: exit 0 (stopped by SIGTERM) or 130
// (it got the terminal's SIGINT too), or killed by a stop signal before it had its handlers
// installed (a process still starting). Anything else is a failure, stop or no stop.
bool stoppedAsAsked(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 130;
  if (!WIFSIGNALED(status)) return false;
  const int sig = WTERMSIG(status);
  return sig == SIGTERM || sig == SIGINT || sig == SIGHUP;
}

// A process group's code: 130 after Ctrl-C, as shells report a command that SIGINT ended;
// otherwise its own (0 when its launcher stopped it with SIGTERM, which is how every run ends).
int exitCodeAfter(int code) { return code == 0 && lastStopSignal() == SIGINT ? 130 : code; }

// The launcher's code when a stop signal ended the run: 128 + the signal, as a shell reports a
// command that the signal ended (130 Ctrl-C, 143 SIGTERM, 129 SIGHUP), so that whoever sent it
// (Slurm's time limit, `docker stop`, systemd, a closed terminal) never reads the cut run as done.
int exitCodeForStopSignal() { return 128 + lastStopSignal(); }

std::string stopSignalName() {
  switch (lastStopSignal()) {
    case SIGINT:
      return "Ctrl-C";
    case SIGHUP:
      return "SIGHUP (its terminal closed)";
    default:
      return "SIGTERM";
  }
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
    if (scene_.processesStepThemselves()) command.argv.push_back("--own-clock");
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
    if (stopRequested() && stoppedAsAsked(exit->status)) return {};
    killed_ = killed_ || WIFSIGNALED(exit->status);
    const std::string what =
        "process '" + process + "' (pid " + std::to_string(exit->pid) + ") " + describeExitStatus(exit->status);
    if (scene_.on_crash == CrashPolicy::kRestart && !stopRequested() && restarts_[process] < scene_.max_restarts) {
      ++restarts_[process];
      std::cerr << "uampc: " << what << "; restarting it (" << restarts_[process] << " of " << scene_.max_restarts
                << ")\n";
      start(process);
      return {};
    }
    failed_ = true;
    return what;
  }

  // Asks every process to stop, waits kStopWait, and kills those that do not.
  void stopAll() {
    children_.signalAll(SIGTERM);
    const auto deadline = ChildProcesses::Clock::now() + kStopWait;
    while (!children_.empty()) {
      const auto exit = children_.waitForExit(deadline);
      if (!exit) {
        for (const auto& [pid, name] : children_.running())
          std::cerr << "uampc: process '" << name << "' did not stop within " << kStopWait.count()
                    << " s; killing it\n";
        children_.killAll();
        failed_ = killed_ = true;
        break;
      }
      killed_ = killed_ || (WIFSIGNALED(exit->status) && !stoppedAsAsked(exit->status));
      const bool clean = WIFEXITED(exit->status) && WEXITSTATUS(exit->status) == 0;
      if (!clean && !(stopRequested() && stoppedAsAsked(exit->status))) {
        std::cerr << "uampc: process '" << exit->name << "' " << describeExitStatus(exit->status)
                  << " while stopping\n";
        failed_ = true;
      }
    }
  }

  bool empty() const { return children_.empty(); }
  bool failed() const { return failed_; }
  // Whether a process died by a signal (crashed, or killed by someone or by stopAll): it left its
  // shared-memory segments behind.
  bool someKilled() const { return killed_; }

 private:
  const Scene& scene_;
  const LaunchOptions& options_;
  ChildProcesses children_;
  std::map<std::string, int> restarts_;
  bool failed_ = false;
  bool killed_ = false;
};

// The output directory removed (or replaced) during the run: the outputs written from then on would
// go nowhere, and the run's results would be silently lost.
std::string outputDirectoryProblem(const std::string& output_directory) {
  if (output_directory.empty() || isDirectory(output_directory)) return {};
  return "the output directory " + output_directory + " was removed during the run; its outputs are lost";
}

// After a process died by a signal: its Fast DDS segments, which nobody else would remove.
void removeWhatKilledProcessesLeft() {
  if (const int removed = removeAbandonedSharedMemorySegments(); removed > 0) {
    std::cerr << "uampc: removed " << removed << " shared-memory segment(s) that killed processes left in /dev/shm\n";
  }
}

// A process group asked to stop that does not (a component hung in a callback) ends itself after
// kStopGrace. The launcher kills such a process after kStopWait (stopAll); this is for when the launcher
// died first (killed, crashed): the process got SIGTERM through PR_SET_PDEATHSIG, and nobody would
// ever kill it; a lockstep one would hold its DDS domain, a test's pipes or a terminal forever.
constexpr std::chrono::seconds kStopGrace{30};
void endIfTheStopHangs(const std::string& process) {
  std::thread([process] {
    while (!stopRequested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::this_thread::sleep_for(kStopGrace);
    std::cerr << "uampc: process '" << process << "' did not stop within " << kStopGrace.count()
              << " s of being asked to (a component is hung); ending it" << std::endl;
    std::_Exit(1);  // the hung component holds the main thread: no destructor would finish
  }).detach();
}

// The file that shows DIR already holds a run (its record or its metrics); empty if none. An empty
// or unrelated directory is fine: only a run's own files say a run would be overwritten.
std::string earlierRunIn(const std::string& directory) {
  for (const char* name : {run_files::kRunInfoFile, run_files::kMetricsFile}) {
    const std::string file = run_files::inDirectory(directory, name);
    if (pathExists(file)) return file;
  }
  return {};
}

// A run is not written over another without --overwrite (docs/decisions/no-silent-overwrite.md):
// the earlier run's outputs would be replaced file by file, silently.
bool refusesEarlierRun(const LaunchOptions& options) {
  if (options.output_directory.empty() || options.overwrite) return false;
  const std::string file = earlierRunIn(options.output_directory);
  if (file.empty()) return false;
  std::cerr << "uampc: --out " << options.output_directory << " already holds a run (" << file
            << "); give --overwrite to write over it, or choose another directory; nothing was started\n";
  return true;
}

}  // namespace

// What a run on a domain is, for a launch the domain's lock refuses.
static std::string runDescription(const LaunchOptions& options) {
  const std::time_t now = std::time(nullptr);
  char started[32] = {};
  std::strftime(started, sizeof started, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  return "uampc launch " + options.scene_path + ", pid " + std::to_string(getpid()) + ", started " + started;
}

// The run's record in its output directory (run_record.hpp); false, said, when it cannot be written.
static bool recordRun(const Scene& scene, const LaunchOptions& options) {
  try {
    fs::create_directories(options.output_directory);
    writeRunRecord(scene, options);
    return true;
  } catch (const std::exception& e) {
    std::cerr << "uampc: " << e.what() << "; nothing was started\n";
    return false;
  }
}

int launch(const LaunchOptions& options) {
  // First: a Ctrl-C from here on ends the launch with 130, however far it got.
  catchStopSignals();
  ComponentCatalog catalog;
  bool ok = false;
  const Scene scene = loadOrReport(options, catalog, ok);
  // Only here, not in run-process and clock: launch starts those, and they would repeat them.
  for (const auto& w : scene.warnings) std::cerr << w << "\n";
  if (!ok) return 2;
  // Before anything of this run exists: a run already on the domain must not hear of this one.
  std::string holder;
  std::optional<DomainRunLock> domain_lock;
  try {
    if (auto taken = DomainRunLock::take(scene.domain_id, runDescription(options), &holder)) {
      domain_lock.emplace(std::move(*taken));
    }
  } catch (const LockFileError& e) {
    // Without the lock a second run could join this one's domain: refuse rather than run unguarded.
    std::cerr << "uampc: " << printableText(e.what()) << "; without it two runs could share DDS domain "
              << scene.domain_id << ", so nothing was started\n";
    return 1;
  }
  if (!domain_lock) {
    std::cerr << "uampc: another run is on DDS domain " << scene.domain_id << " ("
              << (holder.empty() ? "its launcher did not say which" : holder)
              << "); two runs on one domain hear each other's clock and topics, so give this one its own domain_id "
                 "(--set domain_id=N); nothing was started\n";
    return 1;
  }
  if (options.viewer.enabled) {
    if (const std::string problem = viewerAddressProblem(options.viewer); !problem.empty()) {
      std::cerr << "uampc: --view: " << problem << "; nothing was started\n";
      return 1;
    }
  }
  if (refusesEarlierRun(options)) return 1;
  if (!options.output_directory.empty() && !recordRun(scene, options)) return 1;
  if (stopRequested()) return exitCodeForStopSignal();  // stopped while loading: nothing to stop

  std::cerr << "uampc: scene '" << scene.name << "' (" << scene.components.size() << " components, "
            << scene.processes().size() << " process(es), "
            << (scene.clock.mode == ClockMode::kLockstep ? "lockstep" : "real time") << ", DDS domain "
            << scene.domain_id << ")\n";
  // Before the processes, so that a client sees the run from its first step.
  std::unique_ptr<ViewerProcess> viewer;
  if (options.viewer.enabled) {
    viewer = std::make_unique<ViewerProcess>(options.viewer, scene.domain_id, scene.security_directory);
  }
  ProcessSupervisor supervisor(scene, options);
  for (const auto& process : scene.processes()) supervisor.start(process);

  // What ends a run early: a process or the viewer that failed, or the output directory gone.
  // The directory once a second: the clock asks every step, and a stat per step would be waste.
  auto next_directory_check = std::chrono::steady_clock::now();
  auto problem = [&] {
    // A run asked to be watched fails without its viewer (docs/decisions/run-fails-with-its-viewer.md).
    std::string what = viewer ? viewer->poll() : std::string();
    if (what.empty()) what = supervisor.poll();
    if (what.empty() && std::chrono::steady_clock::now() >= next_directory_check) {
      next_directory_check = std::chrono::steady_clock::now() + std::chrono::seconds(1);
      what = outputDirectoryProblem(options.output_directory);
    }
    return what;
  };
  std::string error;
  if (scene.clock.mode == ClockMode::kLockstep) {
    const ClockResult result = runLockstepClock(
        scene, stopFlag(), problem, scene.processesStepThemselves() ? ClockHost::kInTheProcess : ClockHost::kHere);
    // Stopped while the processes were starting is no failure: the user asked.
    if (!result.ok && !stopRequested()) error = result.error;
    std::cerr << "uampc: " << result.sim_seconds << " s of sim time in " << result.wall_seconds << " s ("
              << (result.wall_seconds > 0 ? result.sim_seconds / result.wall_seconds : 0.0)
              << "x real time), after a start of " << result.startup_seconds << " s\n";
  } else {
    const auto start = std::chrono::steady_clock::now();
    while (!stopRequested()) {
      error = problem();
      if (!error.empty() || supervisor.empty()) break;
      if (scene.clock.duration_s > 0 &&
          std::chrono::steady_clock::now() - start > std::chrono::duration<double>(scene.clock.duration_s)) {
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  supervisor.stopAll();
  viewer.reset();
  if (supervisor.someKilled()) removeWhatKilledProcessesLeft();
  if (!error.empty()) {
    std::cerr << "uampc: run failed: " << error << "\n";
    return 1;
  }
  // A stop signal wins over a process that then failed to stop cleanly (said above): it ended the run.
  if (stopRequested()) {
    std::cerr << "uampc: stopped by " << stopSignalName()
              << (scene.clock.duration_s > 0 ? "; the run was cut short of its end (metrics.json says so)" : "")
              << "\n";
    return exitCodeForStopSignal();
  }
  return supervisor.failed() ? 1 : 0;
}

int runClockCommand(const LaunchOptions& options) {
  catchStopSignals();
  ComponentCatalog catalog;
  bool ok = false;
  const Scene scene = loadOrReport(options, catalog, ok);
  if (!ok) return 2;
  if (scene.clock.mode != ClockMode::kLockstep) {
    std::cerr << "uampc: scene " << options.scene_path << " runs in real time; it has no clock to run\n";
    return 2;
  }
  const ClockResult result = runLockstepClock(scene, stopFlag(), [] { return std::string(); });
  if (!result.ok && !stopRequested()) {
    std::cerr << "uampc: run failed: " << result.error << "\n";
    return 1;
  }
  return exitCodeAfter(0);
}

int runProcessCommand(const LaunchOptions& options, const std::string& process, bool own_clock) {
  catchStopSignals();
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
  if (own_clock && !scene.processesStepThemselves()) {
    std::cerr << "uampc: --own-clock lets the process groups of a lockstep scene with clock.in_process: true step "
                 "themselves; this scene "
              << (scene.clock.mode == ClockMode::kLockstep ? "has clock.in_process: false" : "runs in real time")
              << "\n";
    return 2;
  }
  endIfTheStopHangs(process);
  // 130 on Ctrl-C, like launch: the launcher counts it as a clean stop when it was stopping too.
  return exitCodeAfter(runProcessGroup(scene, process, options.output_directory, stopFlag(), own_clock));
}

}  // namespace uampc
