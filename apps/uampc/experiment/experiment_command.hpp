// `uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--domain-base N]
//  [--set NAME=VALUE ...] [--dry-run] [--backend local|slurm ...]`, `uampc experiment --collect DIR`: validates the
//  experiment and every scene it runs, runs the matrix
// (experiment_runner.hpp), and writes DIR/results.json, DIR/results.md and DIR/report/index.html.
// --dry-run stops after validation and prints every planned run's command line.
// The command line is parsed in main.cpp; this file has what the command does with it.
#pragma once

#include "cli/command_set.hpp"

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

namespace uampc::app {

// Fast DDS maps domain ids 0..232 to ports; each job of an experiment runs on a domain of its own.
constexpr int kHighestDomainId = 232;
constexpr int kDefaultDomainBase = 100;
constexpr int kMostJobs = kHighestDomainId - kDefaultDomainBase + 1;

struct ExperimentOptions {
  std::string experiment_file;  // empty with --collect and --run-task
  std::string output_directory;
  std::string data_directory;  // as given; ${data_dir} becomes its absolute path
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int domain_base = kDefaultDomainBase;
  bool dry_run = false;
  std::vector<std::string> overrides;  // --set, as given: every run gets them
  std::string backend = "local";       // local (child processes) or slurm (slurm_backend.hpp)
  std::string partition;               // slurm: --partition
  std::string time_limit;              // slurm: --time per run
  std::vector<std::string> sbatch_options;
  bool no_wait = false;           // slurm: submit only
  bool plan_only = false;         // write DIR/experiment.json for another scheduler, run nothing
  std::string collect_directory;  // --collect DIR: results from DIR's run directories (experiment_collect.hpp)
  long run_task = -1;             // --run-task K: run plan entry K of --out (experiment_task.hpp)
};

// What is wrong with options that parsed (a --set the experiment owns or that is no NAME=VALUE,
// domains past kHighestDomainId), as a message for the user; empty if nothing.
std::string experimentOptionsError(const ExperimentOptions& options);

// Exit codes: 0 every run finished (run_completion.hpp: exited 0 and reached its scene's end), 1 a
// run failed, was cut short or did not finish, 2 invalid experiment, --out held by another
// experiment (output_lock.hpp) or a plan whose run directories are not inside --out/runs
// (plan_directories.hpp), 130 Ctrl-C (what finished is still written to the results). --collect
// and --run-task are dispatched to their own commands.
int experimentCommand(const ExperimentOptions& options);

// `uampc experiment` and its options.
void addExperimentCommand(CommandSet& commands);

}  // namespace uampc::app
