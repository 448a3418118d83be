#include "uampc/evaluator/trajectory_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace uampc::evaluator {

TrajectoryEvaluator::TrajectoryEvaluator(GroundTruthLookup ground_truth, TrajectoryEvaluatorConfig config)
    : ground_truth_(std::move(ground_truth)), config_(std::move(config)) {
  if (!ground_truth_) throw std::invalid_argument("TrajectoryEvaluator: no ground-truth lookup");
  for (const double d : config_.rpe_segment_lengths) {
    if (!(d > 0.0) || !std::isfinite(d)) {
      throw std::invalid_argument("TrajectoryEvaluator: RPE segment lengths must be > 0 m, got " + std::to_string(d));
    }
  }
}

bool TrajectoryEvaluator::addEstimate(double time, const Eigen::Isometry3d& estimate) {
  ++estimates_seen_;
  if (!std::isfinite(time) || !estimate.matrix().allFinite()) {
    ++invalid_;
    return false;
  }
  const std::optional<Eigen::Isometry3d> truth = ground_truth_(time);
  if (!truth) {
    ++unpaired_;
    return false;
  }
  if (!truth->matrix().allFinite()) {
    ++invalid_;
    return false;
  }
  ate_.add(time, estimate.translation(), truth->translation());
  rpe_.add(time, estimate, *truth);
  estimates_.push_back({time, estimate});
  ground_truths_.push_back({time, *truth});
  return true;
}

TrajectoryReport TrajectoryEvaluator::report() const {
  TrajectoryReport report;
  report.estimates = estimates_seen_;
  report.paired = estimates_.size();
  report.unpaired = unpaired_;
  report.invalid = invalid_;
  report.ate = ate_.report();
  for (const double d : config_.rpe_segment_lengths) report.rpe.push_back(rpe_.report(d));
  report.speed_error = speedError(estimates_, ground_truths_);
  report.distance = pathLength(ground_truths_);
  return report;
}

double pathLength(std::vector<TimedPose> poses) {
  std::stable_sort(poses.begin(), poses.end(), [](const TimedPose& a, const TimedPose& b) { return a.time < b.time; });
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i)
    length += (poses[i].pose.translation() - poses[i - 1].pose.translation()).norm();
  return length;
}

}  // namespace uampc::evaluator
