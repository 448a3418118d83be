// Pairs each estimated pose with the ground truth at its exact time and feeds ATE and RPE.
//
// This is the one place where estimates meet ground truth. An estimate whose time the ground
// truth does not cover is counted as unpaired, never paired with a pose of another time. Call
// addEstimate once the ground truth covers the estimate's time (a streaming caller buffers
// estimates until then, see PoseInterpolator::endTime()).
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "uampc/evaluator/absolute_trajectory_error.hpp"
#include "uampc/evaluator/relative_pose_error.hpp"
#include "uampc/evaluator/speed_error.hpp"
#include "uampc/evaluator/timed_pose.hpp"

namespace uampc::evaluator {

struct TrajectoryEvaluatorConfig {
  std::vector<double> rpe_segment_lengths{10.0, 100.0};  // m
};

struct TrajectoryReport {
  std::size_t estimates = 0;  // every addEstimate call
  std::size_t paired = 0;
  std::size_t unpaired = 0;  // no ground truth at the estimate's time
  std::size_t invalid = 0;   // non-finite time or pose
  AteReport ate;
  std::vector<RpeReport> rpe;  // one per configured segment length, in that order
  // Speed over 1 s baselines against the truth's; a runaway is an error above 1 m/s.
  SpeedErrorReport speed_error;
  // m, the ground truth's path length over the evaluated span: ATE in proportion to how far the
  // run went (runs of different scenes and lengths become comparable).
  double distance = 0.0;
};

// Length of the polyline through the poses' positions, given in time order, m. At the
// estimates' rate (10 Hz) the chords differ from the arc by far less than the ATE's precision.
double pathLength(const std::vector<TimedPose>& poses);

class TrajectoryEvaluator {
 public:
  explicit TrajectoryEvaluator(GroundTruthLookup ground_truth, TrajectoryEvaluatorConfig config = {});

  // Returns true when the estimate was paired with ground truth.
  bool addEstimate(double time, const Eigen::Isometry3d& estimate);

  TrajectoryReport report() const;
  // The ATE's two RMSEs as report() has them, without building the report: what the evaluator
  // publishes every report_period (AbsoluteTrajectoryError::rmse).
  AteRmse ateRmse() const { return ate_.rmse(); }

  // The paired estimates and the ground truth at their times, in arrival order (for TUM files).
  const std::vector<TimedPose>& pairedEstimates() const { return estimates_; }
  const std::vector<TimedPose>& pairedGroundTruth() const { return ground_truths_; }

 private:
  GroundTruthLookup ground_truth_;
  TrajectoryEvaluatorConfig config_;
  AbsoluteTrajectoryError ate_;
  // The pairs, in arrival order; the RPE is computed from them in report() (it keeps no copy).
  std::vector<TimedPose> estimates_;
  std::vector<TimedPose> ground_truths_;
  std::size_t estimates_seen_ = 0;
  std::size_t unpaired_ = 0;
  std::size_t invalid_ = 0;
};

}  // namespace uampc::evaluator
