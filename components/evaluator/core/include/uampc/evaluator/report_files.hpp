// The evaluator's reports in the run files' shapes (libs/run_files): metrics.json's
// summaries and the rows of ate.csv and the CMPLT window files.
#pragma once

#include <string>
#include <vector>

#include "uampc/evaluator/absolute_trajectory_error.hpp"
#include "uampc/evaluator/completeness.hpp"
#include "uampc/evaluator/trajectory_evaluator.hpp"
#include "uampc/run_files/metrics_file.hpp"

namespace uampc::evaluator {

run_files::ErrorSummary toSummary(const ErrorStatistics& statistics);
// Counts, the distance (the ground truth's path length over the evaluated span), ATE (unaligned:
// the paper's ATE is ate.unaligned_m.rmse; aligned), RPE per segment length, the speed error.
run_files::TrajectorySummary toSummary(const TrajectoryReport& report);
// CMPLT (the mean over complete windows) and counts; the per-window counts go to CSV.
run_files::CompletenessSummary toSummary(const CompletenessReport& report);

void writeAteSeriesCsv(const std::string& path, const std::vector<AteSample>& series);
void writeCompletenessWindowsCsv(const std::string& path, const std::vector<CompletenessWindow>& windows);

}  // namespace uampc::evaluator
