#include "experiment/experiment_eta.hpp"

#include <algorithm>

#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_progress.hpp"

namespace uampc::app {

SimProgress runProgress(const std::string& run_directory) {
  const auto progress = run_files::readRunProgress(run_files::inDirectory(run_directory, run_files::kProgressFile));
  return progress ? SimProgress{progress->sim_s, progress->total_s} : SimProgress{};
}

double estimateRemainingSeconds(const std::vector<StartedRun>& runs, const std::vector<double>& pending_total_s,
                                int jobs) {
  double simulated = 0.0, wall = 0.0, known_total = 0.0, left = 0.0;
  int known = 0, runs_left = 0;
  for (const StartedRun& r : runs) {
    simulated += r.progress.done_s;
    wall += r.wall_s;
    if (r.progress.total_s > 0) {
      known_total += r.progress.total_s;
      ++known;
      left += std::max(0.0, r.progress.total_s - r.progress.done_s);
      if (r.progress.done_s < r.progress.total_s) ++runs_left;
    }
  }
  if (!(simulated > 0.0) || !(wall > 0.0)) return -1.0;
  const double mean_total = known ? known_total / known : 0.0;
  for (const double total : pending_total_s) {
    left += total > 0 ? total : mean_total;
    ++runs_left;
  }
  if (runs_left == 0) return 0.0;
  const double rate_per_slot = simulated / wall;  // sim seconds per wall second of one slot
  const int slots = std::max(1, std::min(jobs, runs_left));
  return left / (rate_per_slot * slots);
}

}  // namespace uampc::app
