// Absolute trajectory error (ATE): the distance between estimated and ground-truth positions at
// the same times.
//
// The paper's ATE is the RMSE of these distances with no alignment: the LO starts at the ground
// truth's first pose, so drift is what it measures. The RMSE after a rigid Umeyama alignment
// (umeyama.hpp) is reported too, as most benchmarks do. Pairs are independent: the order in which
// they are added does not matter (the series is reported sorted by time).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <limits>
#include <vector>

#include "uampc/evaluator/error_statistics.hpp"

namespace uampc::evaluator {

struct AteSample {
  double time = 0.0;           // s
  double error = 0.0;          // m, unaligned
  double aligned_error = 0.0;  // m, after the Umeyama alignment
};

// The two RMSEs alone (NaN without pairs).
struct AteRmse {
  double unaligned = std::numeric_limits<double>::quiet_NaN();
  double aligned = std::numeric_limits<double>::quiet_NaN();
};

struct AteReport {
  ErrorStatistics unaligned;  // the paper's ATE is unaligned.rmse
  ErrorStatistics aligned;
  Eigen::Isometry3d alignment =
      Eigen::Isometry3d::Identity();  // ground truth = alignment * estimate
  std::vector<AteSample> series;      // sorted by time, for "ATE over time"
};

class AbsoluteTrajectoryError {
 public:
  // One pair: the estimated and the ground-truth position at the same time. Non-finite input is
  // refused (returns false) and counted in rejected().
  bool add(double time, const Eigen::Vector3d& estimate, const Eigen::Vector3d& ground_truth);

  AteReport report() const;
  // report()'s unaligned.rmse and aligned.rmse, the same doubles (the same sums in the same order),
  // without the series and the other statistics: no memory in proportion to the pairs, for a
  // figure published while the run goes on (docs/results/soak.md).
  AteRmse rmse() const;

  std::size_t size() const { return times_.size(); }
  std::size_t rejected() const { return rejected_; }

 private:
  std::vector<double> times_;
  std::vector<Eigen::Vector3d> estimates_;
  std::vector<Eigen::Vector3d> ground_truths_;
  std::size_t rejected_ = 0;
};

}  // namespace uampc::evaluator
