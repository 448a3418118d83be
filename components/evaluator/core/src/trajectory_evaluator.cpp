#include "uampc/evaluator/trajectory_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
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
  {
    RelativePoseError rpe;
    for (std::size_t i = 0; i < estimates_.size(); ++i) {
      rpe.add(estimates_[i].time, estimates_[i].pose, ground_truths_[i].pose);
    }
    for (const double d : config_.rpe_segment_lengths) report.rpe.push_back(rpe.report(d));
  }
  // Pairs may come in any order; the figures below need time order. Sorted once, for both.
  std::vector<std::size_t> order(estimates_.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [this](std::size_t a, std::size_t b) { return estimates_[a].time < estimates_[b].time; });
  std::vector<TimedPose> estimates, truths;
  estimates.reserve(order.size());
  truths.reserve(order.size());
  for (std::size_t i : order) {
    estimates.push_back(estimates_[i]);
    truths.push_back(ground_truths_[i]);
  }
  report.speed_error = speedError(estimates, truths);
  report.distance = pathLength(truths);
  return report;
}

double pathLength(const std::vector<TimedPose>& poses) {
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i)
    length += (poses[i].pose.translation() - poses[i - 1].pose.translation()).norm();
  return length;
}

}  // namespace uampc::evaluator
