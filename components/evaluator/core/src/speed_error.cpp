#include "uampc/evaluator/speed_error.hpp"

#include <algorithm>
#include <cstddef>

namespace uampc::evaluator {

SpeedErrorReport speedError(const std::vector<TimedPose>& estimates, const std::vector<TimedPose>& truths,
                            double baseline, double runaway_threshold) {
  SpeedErrorReport report;
  const std::size_t n = std::min(estimates.size(), truths.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    // The first pose at least `baseline` after pose i (j only moves forward: time increases).
    j = std::max(j, i + 1);
    while (j < n && estimates[j].time - estimates[i].time < baseline) ++j;
    if (j >= n) break;
    const double dt = estimates[j].time - estimates[i].time;
    const Eigen::Vector3d v_estimated = (estimates[j].pose.translation() - estimates[i].pose.translation()) / dt;
    const Eigen::Vector3d v_true = (truths[j].pose.translation() - truths[i].pose.translation()) / dt;
    const double error = (v_estimated - v_true).norm();
    report.max = std::max(report.max, error);
    if (error > runaway_threshold && !report.first_runaway_time) report.first_runaway_time = estimates[j].time;
  }
  return report;
}

}  // namespace uampc::evaluator
