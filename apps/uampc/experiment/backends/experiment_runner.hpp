// Runs an experiment's matrix (scenes x controllers x seeds) as child processes of
// `uampc launch`, at most `jobs` at once. Each run gets its own DDS domain, domain_base + its
// slot (0 .. jobs-1), so parallel runs never see each other's topics; each writes into
// OUT/runs/<scene>/<controller>/seed<K>/ with its stdout and stderr in run.log there.
//
// Resume: a done run (run_completion.hpp: `uampc launch` exited 0 and its metrics reached the
// scene's end) is not run again. Anything else in a run directory is an unfinished, failed or cut
// short run: its directory is emptied and the run retried, by an attempt that holds the run
// (run_attempt.hpp), so that no other experiment or --run-task clears it meanwhile.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"
#include "experiment/run_completion.hpp"
#include "experiment/run_results.hpp"
#include "uampc/runtime/child_processes.hpp"

namespace uampc::app {

struct PlannedRun {
  std::size_t scene = 0;
  std::size_t controller = 0;
  std::uint64_t seed = 0;
  std::string directory;          // relative to the output directory
  std::vector<std::string> args;  // after `uampc`, without domain_id (given at start)
  SceneEnd end;                   // where its sim time must reach to be done
};

// Every run in scene, controller, seed order. `extra_overrides` (the command line's --set) come
// after the experiment's own, so they win. Their ends are the loaded scenes' (sceneEndOf), set
// when the scenes are validated.
std::vector<PlannedRun> planRuns(const Experiment& experiment, const std::vector<std::string>& extra_overrides);

struct RunnerOptions {
  std::string output_directory;
  std::string executable = "/proc/self/exe";  // the uampc binary to launch runs with
  int jobs = 1;
  int domain_base = 100;
  const std::atomic<bool>* interrupted = nullptr;  // set by Ctrl-C: start nothing more, stop runs
};

// A run's result before anything is known of it: which scene, controller, seed and directory.
RunResult plannedResult(const Experiment& experiment, const PlannedRun& run);

// Starts one run as `executable launch ... --out directory --set domain_id=D`, its stdout and
// stderr into the directory's run.log; the directory is an attempt's (beginAttempt, emptied and
// held). Returns its pid; throws std::system_error when no process can be started.
pid_t startRun(ChildProcesses& children, const std::string& executable, const PlannedRun& run,
               const std::string& directory, int domain_id);

// A run's process ended with `wait_status` after `wall_time_s`: writes its done marker (exit 0 and
// metrics.json whose sim time reached `end`) or its failed marker, and fills result's status, exit
// code, failure and figures. `interrupted`: the user stopped it (not a failure of the run).
// Returns "" or, when the marker could not be written, why ("cannot write PATH: REASON"): the
// marker is then absent (markers are written whole or not at all), and a run whose done marker
// is missing counts as failed, to be run again (docs/decisions/run-files-whole-or-absent.md).
std::string recordRunEnd(const std::string& directory, int wait_status, double wall_time_s, bool interrupted,
                         const SceneEnd& end, RunResult& result);

struct RunnerOutcome {
  std::vector<RunResult> results;  // one per planned run, in plan order
  // Empty, or why the experiment stopped early: a file of its own (a run directory, a marker)
  // that could not be written, e.g. on a full disk. The runs then running were stopped as on
  // Ctrl-C, and none was started after.
  std::string error;
};

// Runs what is not complete yet.
RunnerOutcome runAll(const Experiment& experiment, const std::vector<PlannedRun>& plan, const RunnerOptions& options);

}  // namespace uampc::app
