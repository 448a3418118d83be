#include "uampc/evaluator/report_files.hpp"

#include "uampc/evaluator/csv_writer.hpp"

namespace uampc::evaluator {

JsonObject toJson(const ErrorStatistics& statistics) {
  JsonObject json;
  json.set("count", std::uint64_t{statistics.count})
      .set("rmse", statistics.rmse)
      .set("mean", statistics.mean)
      .set("median", statistics.median)
      .set("max", statistics.max);
  return json;
}

JsonObject toJson(const TrajectoryReport& report) {
  JsonObject json;
  json.set("estimates", std::uint64_t{report.estimates})
      .set("paired", std::uint64_t{report.paired})
      .set("unpaired", std::uint64_t{report.unpaired})
      .set("invalid", std::uint64_t{report.invalid})
      .set("distance_m", report.distance);
  JsonObject ate;
  ate.set("unaligned_m", toJson(report.ate.unaligned)).set("aligned_m", toJson(report.ate.aligned));
  json.set("ate", ate);
  for (const RpeReport& rpe : report.rpe) {
    JsonObject segment;
    segment.set("segment_length_m", rpe.segment_length)
        .set("translation_m", toJson(rpe.translation))
        .set("translation_percent", toJson(rpe.translation_percent))
        .set("rotation_deg", toJson(rpe.rotation_deg));
    json.set("rpe_" + formatDouble(rpe.segment_length) + "m", segment);
  }
  JsonObject speed;
  speed.set("max_m_s", report.speed_error.max);
  if (report.speed_error.first_runaway_time) speed.set("first_runaway_time", *report.speed_error.first_runaway_time);
  json.set("speed_error", speed);
  return json;
}

JsonObject toJson(const CompletenessReport& report) {
  JsonObject json;
  json.set("cmplt", report.mean_voxels_per_window)
      .set("complete_windows", std::uint64_t{report.complete_windows})
      .set("windows", std::uint64_t{report.windows.size()})
      .set("total_voxels", std::uint64_t{report.total_voxels})
      .set("scans", std::uint64_t{report.scans})
      .set("points", std::uint64_t{report.points})
      .set("invalid_points", std::uint64_t{report.invalid_points})
      .set("out_of_range_points", std::uint64_t{report.out_of_range_points})
      .set("late_scans", std::uint64_t{report.late_scans})
      .set("invalid_scans", std::uint64_t{report.invalid_scans});
  return json;
}

void writeAteSeriesCsv(const std::string& path, const std::vector<AteSample>& series) {
  CsvWriter csv(path, {"time", "ate_m", "ate_aligned_m"});
  for (const AteSample& s : series) csv.addRow({s.time, s.error, s.aligned_error});
  csv.close();
}

void writeCompletenessWindowsCsv(const std::string& path, const std::vector<CompletenessWindow>& windows) {
  CsvWriter csv(path, {"window", "start", "end", "voxels", "scans", "points", "complete"});
  for (const CompletenessWindow& w : windows) {
    csv.addRow({static_cast<double>(w.index), w.start, w.end, static_cast<double>(w.voxels),
                static_cast<double>(w.scans), static_cast<double>(w.points), w.complete ? 1.0 : 0.0});
  }
  csv.close();
}

}  // namespace uampc::evaluator
