#include "uampc/evaluator/absolute_trajectory_error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "uampc/evaluator/umeyama.hpp"

namespace uampc::evaluator {
namespace {

// One pair's distances, unaligned and after the alignment: the one definition report() and rmse()
// share, so that their RMSEs are the same doubles.
struct PairErrors {
  double unaligned;
  double aligned;
};

PairErrors pairErrors(const Eigen::Vector3d& estimate, const Eigen::Vector3d& ground_truth,
                      const Eigen::Isometry3d& alignment) {
  return {(estimate - ground_truth).norm(), (alignment * estimate - ground_truth).norm()};
}

}  // namespace

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
    const PairErrors e = pairErrors(estimates_[i], ground_truths_[i], report.alignment);
    errors[i] = e.unaligned;
    aligned_errors[i] = e.aligned;
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
    const PairErrors e = pairErrors(estimates_[i], ground_truths_[i], alignment);
    sum_squares += e.unaligned * e.unaligned;
    aligned_sum_squares += e.aligned * e.aligned;
  }
  rmse.unaligned = std::sqrt(sum_squares / static_cast<double>(n));
  rmse.aligned = std::sqrt(aligned_sum_squares / static_cast<double>(n));
  return rmse;
}

}  // namespace uampc::evaluator
