// The evaluator's reports as metrics JSON objects and CSV time series.
#pragma once

#include <string>
#include <vector>

#include "uampc/evaluator/absolute_trajectory_error.hpp"
#include "uampc/evaluator/completeness.hpp"
#include "uampc/evaluator/json_writer.hpp"
#include "uampc/evaluator/trajectory_evaluator.hpp"

namespace uampc::evaluator {

JsonObject toJson(const ErrorStatistics& statistics);
// Counts, "distance_m" (the ground truth's path length over the evaluated span), "ate" (unaligned: the paper's ATE is
// ate.unaligned.rmse; aligned) and "rpe_<d>m" per segment length (d printed without trailing zeros, e.g. rpe_10m).
JsonObject toJson(const TrajectoryReport& report);
// "cmplt" (the mean over complete windows), counts; the per-window counts go to CSV.
JsonObject toJson(const CompletenessReport& report);

// Columns time,ate_m,ate_aligned_m.
void writeAteSeriesCsv(const std::string& path, const std::vector<AteSample>& series);
// Columns window,start,end,voxels,scans,points,complete (complete is 0 or 1).
void writeCompletenessWindowsCsv(const std::string& path, const std::vector<CompletenessWindow>& windows);

}  // namespace uampc::evaluator
