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

// The last "uampc: sim X / Y s" progress line of a `uampc launch` log, if any.
std::optional<SimProgress> lastSimProgress(const std::string& log_text);

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
