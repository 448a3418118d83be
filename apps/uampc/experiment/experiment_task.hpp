// `uampc experiment --run-task K --out DIR [--domain-base N]`: runs entry K of the plan in
// DIR/experiment.json, as one task of a Slurm job array (slurm_backend.hpp) or of a Kubernetes
// Indexed Job (docker/k8s/) does; DIR must be where the submitting machine wrote it (a shared
// filesystem). The run gets the same directory, run.log, progress file and done or failed marker
// as a local run, so that resuming and collecting do not care where it ran.
//
// DDS domain: tasks of one node must not share one, and a node may run tasks of several
// experiments. Each task takes the first domain from N (default 100) to 232 that no other task on
// the node holds, by an exclusive lock on /tmp/uampc/dds-domain-<D>.lock kept while its run lasts
// (released by the kernel however the task ends). Tasks on other nodes may use the same domain:
// a Slurm run's DDS traffic is kept on its own host (slurm_backend.hpp).
#pragma once

#include <string>

namespace uampc::app {

// The --out lock (output_lock.hpp) is not taken: the command that submitted the task may hold it
// while it watches. The task holds its run instead, for as long as it runs (run_attempt.hpp): a
// run another attempt holds (an experiment on DIR, another task) is left alone.
//
// Exit codes: 0 the run finished (run_completion.hpp), 1 it failed or was cut short (its failed
// marker says why), 2 DIR or K is wrong (also a plan whose run directories are not inside
// DIR/runs, plan_directories.hpp), 3 no free DDS domain on this node, 4 another attempt holds the
// run (named), 130 stopped by SIGINT/SIGTERM (Slurm's scancel or time limit).
int experimentTaskCommand(const std::string& output_directory, long task_index, int domain_base);

}  // namespace uampc::app
