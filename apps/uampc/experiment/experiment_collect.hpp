// An experiment's results from its run directories, wherever the runs ran: what
// `uampc experiment --collect DIR` does, and what every backend does once its runs have ended.
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_snapshot.hpp"
#include "experiment/run_results.hpp"

namespace uampc::app {

// One result per planned run, from its directory: finished (a done marker and a readable
// metrics.json) as "ok", a failed marker as "failed" with its reason, anything else as "not_run".
std::vector<RunResult> collectRuns(const ExperimentSnapshot& snapshot, const std::string& output_directory);

// DIR/results.json, DIR/results.md, DIR/report/; the paper's table on stdout, where they are on
// stderr. Returns the exit code of the experiment: 0 every run finished, 1 otherwise.
int writeExperimentOutputs(const Experiment& experiment, const std::vector<RunResult>& results,
                           const std::string& output_directory);

// `uampc experiment --collect DIR`: 2 when DIR holds no readable experiment.json.
int collectCommand(const std::string& output_directory);

}  // namespace uampc::app
