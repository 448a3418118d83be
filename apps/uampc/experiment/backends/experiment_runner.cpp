#include "experiment/backends/experiment_runner.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <system_error>
#include <thread>

#include "experiment/experiment_eta.hpp"
#include "experiment/run_attempt.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/runtime/child_processes.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace uampc::app {

namespace {

std::string duration(double seconds) {
  if (!(seconds >= 0)) return "?";
  const long s = std::lround(seconds);
  char buffer[32];
  if (s >= 3600)
    std::snprintf(buffer, sizeof(buffer), "%ldh%02ldm", s / 3600, s / 60 % 60);
  else if (s >= 60)
    std::snprintf(buffer, sizeof(buffer), "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buffer, sizeof(buffer), "%lds", s);
  return buffer;
}

std::string lastLine(const std::string& text) {
  std::size_t end = text.find_last_not_of("\r\n ");
  if (end == std::string::npos) return "";
  const std::size_t begin = text.find_last_of('\n', end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1,
                     end - (begin == std::string::npos ? 0 : begin + 1) + 1);
}

// One line rewritten in place on a terminal; on a pipe or file, a line every 30 s and at each
// finished run, so that CI logs stay readable.
class Progress {
 public:
  Progress(std::size_t total, std::size_t reused)
      : total_(total), reused_(reused), terminal_(isatty(STDERR_FILENO)), start_(Clock::now()) {}

  // Whether a line is due: every second on a terminal, every 30 s otherwise, or when forced.
  bool due(bool force) const {
    const double since_last = std::chrono::duration<double>(Clock::now() - last_).count();
    return force || since_last >= (terminal_ ? 1.0 : 30.0);
  }
  // eta_s: wall seconds left (estimateRemainingSeconds), negative when not known yet.
  void print(std::size_t finished_now, std::size_t running, std::size_t failed, double eta_s) {
    const auto now = Clock::now();
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const std::size_t remaining = total_ - reused_ - finished_now;
    std::string text = "experiment: " + std::to_string(reused_ + finished_now) + "/" + std::to_string(total_) + " done";
    if (reused_) text += " (" + std::to_string(reused_) + " from before)";
    text += ", " + std::to_string(running) + " running, " + std::to_string(failed) + " failed, elapsed " +
            duration(elapsed) + ", ETA " + (remaining == 0 ? "0s" : duration(eta_s));
    if (terminal_)
      std::cerr << "\r\033[K" << text << std::flush;
    else
      std::cerr << text << "\n";
    line_open_ = terminal_;
  }
  // Messages between progress lines must not land in the middle of one.
  void say(const std::string& message) {
    if (line_open_) std::cerr << "\r\033[K";
    std::cerr << message << "\n";
    line_open_ = false;
    last_ = {};
  }
  void finish() {
    if (line_open_) std::cerr << "\n";
    line_open_ = false;
  }

 private:
  std::size_t total_, reused_;
  bool terminal_;
  bool line_open_ = false;
  Clock::time_point start_, last_{};
};

struct Running {
  std::size_t run;
  int slot;
  Clock::time_point start;
  FileLock attempt;  // the run's, until its end is recorded (run_attempt.hpp)
};

// This process's environment with the run's progress file named in it (the clock writes it).
std::vector<std::string> runEnvironment(const fs::path& progress_file) {
  const std::string name = std::string(run_files::kProgressFileVariable) + "=";
  std::vector<std::string> environment;
  for (char** entry = environ; *entry; ++entry) {
    if (std::string(*entry).rfind(name, 0) != 0) environment.push_back(*entry);
  }
  environment.push_back(name + progress_file.string());
  return environment;
}

// A run: `uampc <args>` with its output in the run directory's log.
ChildCommand runCommand(const std::string& executable, const std::vector<std::string>& args,
                        const fs::path& directory) {
  ChildCommand command;
  command.name = directory.string();
  command.executable = executable;
  command.argv = {"uampc"};
  command.argv.insert(command.argv.end(), args.begin(), args.end());
  command.environment = runEnvironment(directory / run_files::kProgressFile);
  command.log_file = (directory / run_files::kRunLog).string();
  command.exec_failure_message = "uampc experiment: cannot execute the uampc binary\n";
  return command;
}

std::string describeExit(int status) {
  if (WIFEXITED(status)) return "exit code " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + strsignal(WTERMSIG(status));
  return "stopped";
}

// Why a run that ended is not done: how it exited, and how far its metrics got if they stop short.
std::string describeFailure(int status, const std::optional<RunMetrics>& metrics, const SceneEnd& end) {
  const bool exited_0 = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (exited_0 && !metrics) return "exit code 0 but no readable metrics.json";
  const bool short_of_end = metrics && !reachesSceneEnd(metrics->sim_time_s, end);
  return describeExit(status) + (short_of_end ? ", cut short: " + simTimeOfEnd(metrics->sim_time_s, end) : "");
}

}  // namespace

std::vector<PlannedRun> planRuns(const Experiment& experiment, const std::vector<std::string>& extra_overrides) {
  std::vector<PlannedRun> plan;
  for (std::size_t s = 0; s < experiment.scenes.size(); ++s) {
    for (std::size_t c = 0; c < experiment.controllers.size(); ++c) {
      for (const std::uint64_t seed : experiment.seeds) {
        PlannedRun run{s, c, seed, "", {}, {}};
        run.directory =
            "runs/" + experiment.scenes[s].name + "/" + experiment.controllers[c].name + "/seed" + std::to_string(seed);
        run.args = {"launch", experiment.scenes[s].scene_file};
        auto set = [&run](const std::string& text) {
          run.args.push_back("--set");
          run.args.push_back(text);
        };
        if (experiment.duration_s) {
          std::ostringstream d;
          d << *experiment.duration_s;
          set("clock.duration=" + d.str());
        }
        for (const auto& o : experiment.scenes[s].overrides) set(o);
        for (const auto& o : experiment.controllers[c].overrides) set(o);
        for (const auto& o : extra_overrides) set(o);
        set("seed=" + std::to_string(seed));
        plan.push_back(std::move(run));
      }
    }
  }
  return plan;
}

RunResult plannedResult(const Experiment& experiment, const PlannedRun& run) {
  RunResult r;
  r.scene = experiment.scenes[run.scene].name;
  r.controller = experiment.controllers[run.controller].name;
  r.seed = run.seed;
  r.directory = run.directory;
  return r;
}

pid_t startRun(ChildProcesses& children, const std::string& executable, const PlannedRun& run,
               const std::string& directory, int domain_id) {
  std::vector<std::string> args = run.args;
  args.insert(args.end(), {"--out", directory, "--set", "domain_id=" + std::to_string(domain_id)});
  return children.start(runCommand(executable, args, directory));
}

namespace {

// Writes a marker; "" or why it could not (the marker is then absent: text_file.hpp).
std::string tryToWrite(const std::function<void()>& write_marker) {
  try {
    write_marker();
    return "";
  } catch (const std::runtime_error& e) {
    return e.what();
  }
}

}  // namespace

std::string recordRunEnd(const std::string& directory, int wait_status, double wall_time_s, bool interrupted,
                         const SceneEnd& end, RunResult& result) {
  result.exit_code = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
  const std::optional<RunMetrics> metrics = readRunMetrics(directory);
  if (result.exit_code == 0 && metrics && reachesSceneEnd(metrics->sim_time_s, end)) {
    const std::string error = tryToWrite([&] { run_files::writeDoneMarker(directory, wall_time_s); });
    if (error.empty()) {
      result.status = RunStatus::kOk;
      readRunOutputs(directory, result);
      return "";
    }
    // Not done until its marker says so: the next invocation runs it again.
    result.status = RunStatus::kFailed;
    result.failure = "finished, but its done marker could not be written (" + error + ")";
    result.wall_time_s = wall_time_s;
    return error;
  }
  if (interrupted) {
    result.status = RunStatus::kNotRun;  // stopped by Ctrl-C: not a failure of the run
    result.failure = "interrupted";
  } else {
    result.status = RunStatus::kFailed;
    result.failure = describeFailure(wait_status, metrics, end);
    result.wall_time_s = wall_time_s;
    if (metrics) result.metrics = *metrics;  // how far it got, for results.json
  }
  return tryToWrite([&] { run_files::writeFailedMarker(directory, result.failure); });
}

namespace {

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// runAll's state and its steps: the runs of before taken as they are, the others started into
// free slots, each finished one collected, progress reported.
class Scheduler {
 public:
  Scheduler(const Experiment& experiment, const std::vector<PlannedRun>& plan, const RunnerOptions& options)
      : experiment_(experiment),
        plan_(plan),
        options_(options),
        results_(plan.size()),
        slot_busy_(static_cast<std::size_t>(std::max(options.jobs, 1)), false) {}

  RunnerOutcome run() {
    reuseCompleteRuns();
    Progress progress(plan_.size(), plan_.size() - pending_.size());
    progress_ = &progress;
    announceRetries();
    if (pending_.empty()) progress.print(0, 0, 0, 0.0);  // nothing to run: say so
    while (true) {
      if (options_.interrupted && *options_.interrupted && !stopping_) stop();
      if (!stopping_) startPending();
      if (running_.empty()) break;
      report(false);
      const auto exit = children_.pollExit();
      if (!exit) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        continue;
      }
      const auto found = running_.find(exit->pid);
      if (found == running_.end()) continue;  // not a run (the pool only holds runs; kept safe)
      const Running done = std::move(found->second);
      running_.erase(found);
      collect(done, exit->status);  // its attempt's lock is released after its end is recorded
      report(true);
    }
    progress.finish();
    return {results_, error_};
  }

 private:
  fs::path directoryOf(std::size_t run) const { return fs::path(options_.output_directory) / plan_[run].directory; }

  // Done runs of before are read, not run again; the others are pending.
  void reuseCompleteRuns() {
    for (std::size_t i = 0; i < plan_.size(); ++i) {
      RunResult& r = results_[i] = plannedResult(experiment_, plan_[i]);
      const fs::path dir = directoryOf(i);
      const RunCompletion before = runCompletion(dir.string(), plan_[i].end);
      if (before.state == RunState::kDone) {
        r.status = RunStatus::kReused;
        r.exit_code = 0;
        readRunOutputs(dir.string(), r);
        if (r.metrics.sim_time_s > 0) scene_length_s_[plan_[i].scene] = r.metrics.sim_time_s;
        continue;
      }
      r.retried = holdsAnAttempt(dir.string());
      if (r.retried) retry_reasons_[i] = before;
      pending_.push_back(i);
    }
  }

  void announceRetries() {
    for (const auto& [i, before] : retry_reasons_) {
      progress_->say("experiment: retrying " + plan_[i].directory +
                     (before.state == RunState::kFailed ? " (failed before: " + lastLine(before.reason) + ")"
                                                        : " (unfinished before)"));
    }
  }

  void stop() {
    stopping_ = true;
    progress_->say("experiment: interrupted; stopping " + std::to_string(running_.size()) + " run(s)");
    children_.signalAll(SIGINT);  // the launcher stops its run cleanly
  }

  // A file of the experiment's own could not be written (a run directory, a marker): every run
  // after it would go unrecorded, so the experiment stops as on Ctrl-C, and says why.
  void halt(const std::string& error) {
    if (!error_.empty()) return;  // the first says it; the others follow from it
    error_ = error;
    progress_->say("experiment: " + error + "; the experiment stops" +
                   (running_.empty() ? "" : ", and with it " + std::to_string(running_.size()) + " run(s)"));
    stopping_ = true;
    children_.signalAll(SIGINT);
  }

  int freeSlot() const {
    for (std::size_t k = 0; k < slot_busy_.size(); ++k) {
      if (!slot_busy_[k]) return static_cast<int>(k);
    }
    return -1;
  }

  // Starts pending runs while slots are free, each on its slot's DDS domain.
  void startPending() {
    while (next_ < pending_.size()) {
      const int slot = freeSlot();
      if (slot < 0) return;
      const std::size_t i = pending_[next_++];
      std::optional<FileLock> attempt;
      pid_t pid = -1;
      try {
        attempt = beginAttemptAt(i);
        if (!attempt) continue;
        pid = startRun(children_, options_.executable, plan_[i], directoryOf(i).string(), options_.domain_base + slot);
      } catch (const fs::filesystem_error& e) {
        results_[i].status = RunStatus::kNotRun;
        results_[i].failure = "cannot create its directory " + e.path1().string() + ": " + e.code().message();
        halt(results_[i].failure);
        return;
      } catch (const std::system_error& e) {
        fail(i, "cannot start a process: " + e.code().message());
        continue;
      }
      slot_busy_[static_cast<std::size_t>(slot)] = true;
      running_.emplace(pid, Running{i, slot, Clock::now(), std::move(*attempt)});
    }
  }

  // The run held for this experiment and emptied; nullopt, with the run's result said, when
  // another attempt holds it (left alone, not run) or it cannot be held (failed).
  std::optional<FileLock> beginAttemptAt(std::size_t i) {
    AttemptStart start = beginAttempt(options_.output_directory, i, plan_[i], thisProcess() + " (uampc experiment)");
    if (start.lock) return std::move(start.lock);
    RunResult& r = results_[i];
    if (!start.held_by.empty()) {
      r.status = RunStatus::kNotRun;
      r.failure = "being run by " + start.held_by;
      ++finished_now_;
      progress_->say("experiment: " + plan_[i].directory + " left alone: it is " + r.failure);
    } else {
      fail(i, start.error);
    }
    return std::nullopt;
  }

  // A run that failed before it started.
  void fail(std::size_t i, const std::string& why) {
    results_[i].status = RunStatus::kFailed;
    results_[i].failure = why;
    ++failed_;
    ++finished_now_;
    progress_->say("experiment: " + plan_[i].directory + " failed (" + why + ")");
  }

  // A run's process ended: its result, and its done or failed marker.
  void collect(const Running& done, int status) {
    slot_busy_[static_cast<std::size_t>(done.slot)] = false;
    ++finished_now_;
    RunResult& r = results_[done.run];
    const fs::path dir = directoryOf(done.run);
    const double wall = secondsSince(done.start);
    finished_work_.push_back({progressOf(done.run), wall});
    if (const std::string error = recordRunEnd(dir.string(), status, wall, stopping_, plan_[done.run].end, r);
        !error.empty()) {
      halt(error);
    }
    if (r.status != RunStatus::kFailed) return;
    ++failed_;
    const std::string last = lastLine(run_files::readTextFile(dir / run_files::kRunLog));
    progress_->say("experiment: " + plan_[done.run].directory + " failed (" + r.failure + "): " + last +
                   "\n            full log: " + (dir / run_files::kRunLog).string());
  }

  // A run's progress file; it also tells its scene's length (every controller and seed of a scene
  // simulates the same time), for the ETA of the scene's pending runs.
  SimProgress progressOf(std::size_t run) {
    const SimProgress p = runProgress(directoryOf(run).string());
    if (p.total_s > 0) scene_length_s_[plan_[run].scene] = p.total_s;
    return p;
  }

  void report(bool force) {
    if (!progress_->due(force)) return;
    std::vector<StartedRun> work = finished_work_;
    for (const auto& [pid, r] : running_) work.push_back({progressOf(r.run), secondsSince(r.start)});
    std::vector<double> pending_lengths;
    for (std::size_t k = next_; k < pending_.size(); ++k) {
      const auto known = scene_length_s_.find(plan_[pending_[k]].scene);
      pending_lengths.push_back(known == scene_length_s_.end() ? -1.0 : known->second);
    }
    progress_->print(finished_now_, running_.size(), failed_,
                     estimateRemainingSeconds(work, pending_lengths, options_.jobs));
  }

  const Experiment& experiment_;
  const std::vector<PlannedRun>& plan_;
  const RunnerOptions& options_;
  std::vector<RunResult> results_;
  std::vector<std::size_t> pending_;              // runs to start, in plan order
  std::map<std::size_t, RunCompletion> retry_reasons_;  // pending runs an earlier attempt left
  std::size_t next_ = 0;                          // the next of pending_ to start
  std::map<std::size_t, double> scene_length_s_;  // scene -> sim seconds, once known
  ChildProcesses children_;
  std::map<pid_t, Running> running_;  // the runs of children_, by pid
  std::vector<bool> slot_busy_;
  std::size_t finished_now_ = 0, failed_ = 0;
  std::vector<StartedRun> finished_work_;  // for the ETA: the runs finished in this invocation
  Progress* progress_ = nullptr;
  bool stopping_ = false;
  std::string error_;  // why the experiment stopped early (halt); empty: it did not
};

}  // namespace

RunnerOutcome runAll(const Experiment& experiment, const std::vector<PlannedRun>& plan, const RunnerOptions& options) {
  return Scheduler(experiment, plan, options).run();
}

}  // namespace uampc::app
