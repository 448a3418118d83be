#include "uampc/evaluator/report_files.hpp"

#include "uampc/run_files/time_series.hpp"

namespace uampc::evaluator {

run_files::ErrorSummary toSummary(const ErrorStatistics& s) { return {s.count, s.rmse, s.mean, s.median, s.max}; }

run_files::TrajectorySummary toSummary(const TrajectoryReport& report) {
  run_files::TrajectorySummary summary;
  summary.estimates = report.estimates;
  summary.paired = report.paired;
  summary.unpaired = report.unpaired;
  summary.invalid = report.invalid;
  summary.distance_m = report.distance;
  summary.ate = {toSummary(report.ate.unaligned), toSummary(report.ate.aligned)};
  for (const RpeReport& rpe : report.rpe) {
    summary.rpe.push_back({rpe.segment_length, toSummary(rpe.translation), toSummary(rpe.translation_percent),
                           toSummary(rpe.rotation_deg)});
  }
  summary.speed_error = {report.speed_error.max, report.speed_error.first_runaway_time};
  return summary;
}

run_files::CompletenessSummary toSummary(const CompletenessReport& report) {
  run_files::CompletenessSummary summary;
  summary.cmplt = report.mean_voxels_per_window;
  summary.complete_windows = report.complete_windows;
  summary.windows = report.windows.size();
  summary.total_voxels = report.total_voxels;
  summary.scans = report.scans;
  summary.points = report.points;
  summary.invalid_points = report.invalid_points;
  summary.out_of_range_points = report.out_of_range_points;
  summary.late_scans = report.late_scans;
  summary.invalid_scans = report.invalid_scans;
  return summary;
}

void writeAteSeriesCsv(const std::string& path, const std::vector<AteSample>& series) {
  std::vector<run_files::AteRow> rows;
  rows.reserve(series.size());
  for (const AteSample& s : series) rows.push_back({s.time, s.error, s.aligned_error});
  run_files::writeRows(path, rows);
}

void writeCompletenessWindowsCsv(const std::string& path, const std::vector<CompletenessWindow>& windows) {
  std::vector<run_files::CompletenessWindowRow> rows;
  rows.reserve(windows.size());
  for (const CompletenessWindow& w : windows) {
    rows.push_back({static_cast<double>(w.index), w.start, w.end, static_cast<double>(w.voxels),
                    static_cast<double>(w.scans), static_cast<double>(w.points), w.complete});
  }
  run_files::writeRows(path, rows);
}

}  // namespace uampc::evaluator
