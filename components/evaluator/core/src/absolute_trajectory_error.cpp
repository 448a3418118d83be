#include "uampc/evaluator/absolute_trajectory_error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "uampc/evaluator/umeyama.hpp"

namespace uampc::evaluator {

bool AbsoluteTrajectoryError::add(double time, const Eigen::Vector3d& estimate,
                                  const Eigen::Vector3d& ground_truth) {
  if (!std::isfinite(time) || !estimate.allFinite() || !ground_truth.allFinite()) {
    ++rejected_;
    return false;
  }
  times_.push_back(time);
  estimates_.push_back(estimate);
  ground_truths_.push_back(ground_truth);
  return true;
}

AteReport AbsoluteTrajectoryError::report() const {
  AteReport report;
  report.alignment = umeyamaAlignment(estimates_, ground_truths_);
  const std::size_t n = times_.size();
  std::vector<double> errors(n);
  std::vector<double> aligned_errors(n);
  for (std::size_t i = 0; i < n; ++i) {
    errors[i] = (estimates_[i] - ground_truths_[i]).norm();
    aligned_errors[i] = (report.alignment * estimates_[i] - ground_truths_[i]).norm();
  }

  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [this](std::size_t a, std::size_t b) { return times_[a] < times_[b]; });
  report.series.reserve(n);
  for (const std::size_t i : order)
    report.series.push_back({times_[i], errors[i], aligned_errors[i]});

  report.unaligned = summarize(std::move(errors));
  report.aligned = summarize(std::move(aligned_errors));
  return report;
}

AteRmse AbsoluteTrajectoryError::rmse() const {
  AteRmse rmse;
  const std::size_t n = times_.size();
  if (n == 0) return rmse;
  const Eigen::Isometry3d alignment = umeyamaAlignment(estimates_, ground_truths_);
  double sum_squares = 0.0, aligned_sum_squares = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double error = (estimates_[i] - ground_truths_[i]).norm();
    const double aligned_error = (alignment * estimates_[i] - ground_truths_[i]).norm();
    sum_squares += error * error;
    aligned_sum_squares += aligned_error * aligned_error;
  }
  rmse.unaligned = std::sqrt(sum_squares / static_cast<double>(n));
  rmse.aligned = std::sqrt(aligned_sum_squares / static_cast<double>(n));
  return rmse;
}

}  // namespace uampc::evaluator
