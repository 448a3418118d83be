// The experiment's ETA, from simulated seconds rather than finished runs: runs differ in length by
// minutes (a 600 s trajectory against a 60 s corridor), and counting runs gave no ETA at all until
// the first of them ended.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace uampc::app {

struct SimProgress {
  double done_s = 0.0;   // sim time reached
  double total_s = 0.0;  // sim time the run lasts
};

// How far a run has come, from the progress.json its clock writes (run_files/run_progress.hpp);
// zeros before the clock has written one.
SimProgress runProgress(const std::string& run_directory);

struct StartedRun {
  SimProgress progress;  // total_s <= 0: not known yet
  double wall_s = 0.0;   // wall time it has run (or took)
};

// Wall seconds until every run has finished: the sim time left (of started runs, and of pending
// runs whose length is pending_total_s, <= 0 when not known: the mean known length is used) at the
// sim-seconds-per-wall-second each slot has reached so far, over min(jobs, runs left) slots.
// Negative when nothing has been simulated yet to measure a rate from.
double estimateRemainingSeconds(const std::vector<StartedRun>& unfinished_and_finished_runs,
                                const std::vector<double>& pending_total_s, int jobs);

}  // namespace uampc::app
