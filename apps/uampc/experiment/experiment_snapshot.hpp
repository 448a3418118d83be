// DIR/experiment.json: what an experiment's output directory was made from, written when its runs
// are started (locally or on a cluster). It holds the experiment as loaded (names, seeds, the
// comparison) and every planned run's `uampc launch` arguments, so that
//  - a Slurm array task runs plan entry K with nothing but DIR (`uampc experiment --run-task K`),
//    on a node that need not see the experiment file or its ${data_dir};
//  - `uampc experiment --collect DIR` builds the results wherever the runs ran.
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"
#include "experiment/backends/experiment_runner.hpp"

namespace uampc::app {

inline constexpr char kExperimentSnapshotFile[] = "experiment.json";

struct ExperimentSnapshot {
  Experiment experiment;
  std::vector<PlannedRun> plan;
};

// Writes DIR/experiment.json (atomically: a task never reads half a file); throws
// std::runtime_error naming the file when it cannot.
void writeExperimentSnapshot(const std::string& output_directory, const ExperimentSnapshot& snapshot);

// Reads it back; throws ExperimentError naming the file and what is wrong (missing, not JSON, a
// field missing or of the wrong type, an older version, a run whose arguments are not a launch of
// its scene, run directories not inside DIR/runs: plan_directories.hpp).
ExperimentSnapshot readExperimentSnapshot(const std::string& output_directory);

}  // namespace uampc::app
