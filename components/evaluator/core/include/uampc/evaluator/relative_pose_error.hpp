// Relative pose error (RPE) over segments of a given path length, KITTI-like.
//
// Definition. Poses are sorted by time; s_i is the distance travelled along the ground truth up to
// pose i (sum of the straight steps between consecutive ground-truth positions). For every start
// pose i, j is the first pose with s_j - s_i >= d (no segment when the run ends before). With G the
// ground truth and E the estimate, the segment's error is
//     Delta = (G_i^-1 G_j)^-1 (E_i^-1 E_j),
// translational error ||trans(Delta)|| (m), rotational error angle(Delta) (deg), and the relative
// translational error 100 * ||trans(Delta)|| / (s_j - s_i) (%). KITTI divides by the nominal d
// and starts a segment every 10th frame; here every pose starts one and the actual length of the
// segment is used, so a constant scale drift k gives exactly 100 k % on a straight line.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "uampc/evaluator/error_statistics.hpp"

namespace uampc::evaluator {

struct RpeReport {
  double segment_length = 0.0;          // m, d
  ErrorStatistics translation;          // m per segment
  ErrorStatistics translation_percent;  // % of the segment's length; its mean is KITTI's figure
  ErrorStatistics rotation_deg;         // deg per segment
};

class RelativePoseError {
 public:
  // One pair: the estimated and the ground-truth pose at the same time. Non-finite input is
  // refused (returns false) and counted in rejected(). Any order; equal times are harmless.
  bool add(double time, const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& ground_truth);

  // segment_length d > 0 (m), e.g. 10 and 100; throws std::invalid_argument otherwise.
  RpeReport report(double segment_length) const;

  std::size_t size() const { return pairs_.size(); }
  std::size_t rejected() const { return rejected_; }

 private:
  struct Pair {
    double time;
    Eigen::Isometry3d estimate;
    Eigen::Isometry3d ground_truth;
  };
  std::vector<Pair> pairs_;
  std::size_t rejected_ = 0;
};

}  // namespace uampc::evaluator
