// progress.json: how far a run's lockstep clock has come, for the experiment's ETA. The clock
// rewrites it (atomically: a reader never sees half a file) about once a second of wall time when
// the environment variable kProgressFileVariable (run_directory.hpp) names the file.
#pragma once

#include <optional>
#include <string>

namespace uampc::run_files {

struct RunProgress {
  double sim_s = 0.0;     // sim time reached
  double total_s = 0.0;   // sim time the run lasts; 0: until stopped
  double wall_s = 0.0;    // wall time the clock has run
  bool finished = false;  // the clock's last word
};

// Writes path by renaming a file written beside it; throws std::runtime_error naming path.
void writeRunProgress(const std::string& path, const RunProgress& progress);
// nullopt when the file is missing or unreadable.
std::optional<RunProgress> readRunProgress(const std::string& path);

}  // namespace uampc::run_files
