// `uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--domain-base N]
//  [--set NAME=VALUE ...] [--dry-run]`: validates the experiment and every scene it runs, runs the matrix
// (experiment_runner.hpp), and writes DIR/results.json, DIR/results.md and DIR/report/index.html.
// --dry-run stops after validation and prints every planned run's command line.
#pragma once

#include <string>
#include <vector>

namespace uampc::app {

// Exit codes: 0 every run finished, 1 a run failed, 2 invalid experiment or command line,
// 130 Ctrl-C (what finished is still written to the results).
int experimentCommand(const std::vector<std::string>& args);

}  // namespace uampc::app
