#include "uampc/evaluator/relative_pose_error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace uampc::evaluator {

namespace {

bool isFinite(const Eigen::Isometry3d& pose) { return pose.matrix().allFinite(); }

}  // namespace

bool RelativePoseError::add(double time, const Eigen::Isometry3d& estimate,
                            const Eigen::Isometry3d& ground_truth) {
  if (!std::isfinite(time) || !isFinite(estimate) || !isFinite(ground_truth)) {
    ++rejected_;
    return false;
  }
  pairs_.push_back({time, estimate, ground_truth});
  return true;
}

RpeReport RelativePoseError::report(double segment_length) const {
  if (!(segment_length > 0.0) || !std::isfinite(segment_length)) {
    throw std::invalid_argument("RelativePoseError: segment length must be > 0 m, got " +
                                std::to_string(segment_length));
  }
  std::vector<Pair> pairs = pairs_;
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& a, const Pair& b) { return a.time < b.time; });

  // Distance travelled along the ground truth up to each pose.
  std::vector<double> travelled(pairs.size(), 0.0);
  for (std::size_t i = 1; i < pairs.size(); ++i) {
    travelled[i] =
        travelled[i - 1] +
        (pairs[i].ground_truth.translation() - pairs[i - 1].ground_truth.translation()).norm();
  }

  std::vector<double> translation;
  std::vector<double> percent;
  std::vector<double> rotation_deg;
  std::size_t j = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    // travelled is non-decreasing, so the end of the segment only moves forward with i.
    j = std::max(j, i + 1);
    while (j < pairs.size() && travelled[j] - travelled[i] < segment_length) ++j;
    if (j >= pairs.size()) break;
    const Eigen::Isometry3d truth_motion = pairs[i].ground_truth.inverse() * pairs[j].ground_truth;
    const Eigen::Isometry3d estimated_motion = pairs[i].estimate.inverse() * pairs[j].estimate;
    const Eigen::Isometry3d delta = truth_motion.inverse() * estimated_motion;
    const double t_err = delta.translation().norm();
    translation.push_back(t_err);
    percent.push_back(100.0 * t_err / (travelled[j] - travelled[i]));
    rotation_deg.push_back(Eigen::AngleAxisd(delta.rotation()).angle() * 180.0 / M_PI);
  }

  RpeReport report;
  report.segment_length = segment_length;
  report.translation = summarize(std::move(translation));
  report.translation_percent = summarize(std::move(percent));
  report.rotation_deg = summarize(std::move(rotation_deg));
  return report;
}

}  // namespace uampc::evaluator
