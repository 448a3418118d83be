// `uampc experiment EXP.yaml --out DIR --backend slurm`: the experiment's unfinished runs as one
// Slurm job array, one array task per run (`uampc experiment --run-task K --out DIR`,
// experiment_task.hpp). DIR must be on a filesystem the compute nodes share, and the uampc binary
// at the same path there.
//
//  - Submission: DIR/experiment.json (the plan), DIR/slurm/host_only_dds.xml, then `sbatch
//    --array=<the unfinished runs' plan indices>`; each task's output in DIR/slurm/task-<job>_<k>.out;
//    every submitted job id appended to DIR/slurm/jobs, and sbatch's command and answer to
//    DIR/slurm/submissions.log. A job that cannot be recorded there (a full disk) is cancelled and
//    the experiment stops naming the file (docs/decisions/run-files-whole-or-absent.md).
//  - DDS stays on each task's host: a scene without a dds_profile of its own runs with
//    host_only_dds.xml (shared memory, and UDP on 127.0.0.1 only), so that runs on different
//    nodes never discover each other even on the same domain; a scene with its own profile keeps
//    it, and must keep its traffic on the host itself (a warning says so).
//  - Progress: from the run directories (done and failed markers, run logs) and squeue; at the
//    end, how the tasks ended from sacct where the cluster keeps accounting (slurmdbd), else squeue.
//  - Resume: running the same command again submits only the runs not done (run_completion.hpp);
//    it refuses while a job it submitted before is still queued or running.
//  - Whose DIR: the command holds DIR's --out lock while it submits, watches and collects (with
//    --no-wait, until it has submitted); each task holds only its own run (experiment_task.hpp),
//    so that no other experiment clears a run a task is running (output_lock.hpp).
//  - Ctrl-C while watching stops watching, not the job (`scancel <job>` does that);
//    `uampc experiment --collect DIR` builds the results later.
#pragma once

#include <string>
#include <vector>

#include "experiment/backends/backend_outcome.hpp"
#include "experiment/experiment_snapshot.hpp"

namespace uampc::app {

struct SlurmOptions {
  std::string partition;                   // --partition; empty: the cluster's default
  std::string time_limit;                  // --time, per task; empty: the partition's default
  std::vector<std::string> sbatch_options;  // more sbatch options, as given (--sbatch-option)
  bool wait = true;                        // watch the job and collect the results (--no-wait: only submit)
  int domain_base = 100;                   // the first DDS domain a task tries on its node
  double poll_interval_s = 5.0;            // squeue every this many s while watching
};

inline constexpr char kHostOnlyDdsProfile[] = "slurm/host_only_dds.xml";

// Submits what is unfinished and, unless options.wait is false, watches the job and returns the
// results. snapshot.plan must already carry the host-only dds_profile where it applies
// (hostOnlyDdsOverride, writeHostOnlyDdsProfile). Without results, an exit code as `uampc experiment`'s; 2 also when sbatch is missing or
// refuses the job, or a job of this directory is still active.
BackendOutcome runOnSlurm(const ExperimentSnapshot& snapshot, const std::string& output_directory,
                          const SlurmOptions& options);

// "dds_profile=<DIR>/slurm/host_only_dds.xml", the --set a run gets when its scene has no profile.
std::string hostOnlyDdsOverride(const std::string& output_directory);
// Writes that file.
void writeHostOnlyDdsProfile(const std::string& output_directory);

// "0-3,7,9-10": Slurm's --array list of the given increasing indices.
std::string slurmArraySpec(const std::vector<std::size_t>& indices);

}  // namespace uampc::app
