// An experiment's results from its run directories, wherever the runs ran: what
// `uampc experiment --collect DIR` does, and what every backend does once its runs have ended.
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_snapshot.hpp"
#include "experiment/run_results.hpp"

namespace uampc::app {

// One result per planned run, from its directory (run_completion.hpp): done as "ok"; a failed
// marker, or a done marker whose metrics stop short of the scene's end, as "failed" with the
// reason; anything else as "not_run".
std::vector<RunResult> collectRuns(const ExperimentSnapshot& snapshot, const std::string& output_directory);

// DIR/results.json, DIR/results.md, DIR/report/; the paper's table on stdout, where they are and
// each run not done (by directory, with why) on stderr. Returns the exit code of the experiment:
// 0 every run finished, 1 otherwise.
int writeExperimentOutputs(const Experiment& experiment, const std::vector<RunResult>& results,
                           const std::string& output_directory);

// `uampc experiment --collect DIR`: 2 when DIR holds no readable experiment.json, or another
// command holds DIR (output_lock.hpp).
int collectCommand(const std::string& output_directory);

}  // namespace uampc::app
