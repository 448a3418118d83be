#include "uampc/evaluator/pose_interpolator.hpp"

#include <algorithm>
#include <cmath>

namespace uampc::evaluator {

Eigen::Isometry3d interpolatePose(const TimedPose& a, const TimedPose& b, double time) {
  const double s = (time - a.time) / (b.time - a.time);
  const Eigen::Quaterniond qa(a.pose.rotation());
  const Eigen::Quaterniond qb(b.pose.rotation());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = qa.slerp(s, qb).normalized().toRotationMatrix();  // slerp takes the short way
  pose.translation() = (1.0 - s) * a.pose.translation() + s * b.pose.translation();
  return pose;
}

PoseInterpolator::PoseInterpolator(std::vector<TimedPose> poses) {
  const std::size_t given = poses.size();
  poses.erase(std::remove_if(poses.begin(), poses.end(),
                             [](const TimedPose& p) { return !std::isfinite(p.time); }),
              poses.end());
  std::stable_sort(poses.begin(), poses.end(),
                   [](const TimedPose& a, const TimedPose& b) { return a.time < b.time; });
  poses.erase(std::unique(poses.begin(), poses.end(),
                          [](const TimedPose& a, const TimedPose& b) { return a.time == b.time; }),
              poses.end());
  dropped_ = given - poses.size();
  poses_ = std::move(poses);
}

bool PoseInterpolator::add(const TimedPose& pose) {
  if (!std::isfinite(pose.time)) {
    ++dropped_;
    return false;
  }
  if (poses_.empty() || pose.time > poses_.back().time) {
    poses_.push_back(pose);
    return true;
  }
  const auto at = std::lower_bound(poses_.begin(), poses_.end(), pose.time,
                                   [](const TimedPose& p, double t) { return p.time < t; });
  if (at->time == pose.time) {
    ++dropped_;
    return false;
  }
  poses_.insert(at, pose);
  return true;
}

void PoseInterpolator::dropBefore(double time, std::size_t batch) {
  const auto after = std::upper_bound(poses_.begin(), poses_.end(), time,
                                      [](double t, const TimedPose& p) { return t < p.time; });
  if (after == poses_.begin()) return;
  const auto keep_from = std::prev(after);  // the last pose at or before `time`: lookups at `time` need it
  if (static_cast<std::size_t>(keep_from - poses_.begin()) < batch) return;
  poses_.erase(poses_.begin(), keep_from);
}

std::optional<Eigen::Isometry3d> PoseInterpolator::operator()(double time) const {
  if (poses_.empty() || !(time >= poses_.front().time) || !(time <= poses_.back().time)) {
    return std::nullopt;  // also for NaN
  }
  // First pose at or after time; time is inside, so it exists.
  const auto after = std::lower_bound(poses_.begin(), poses_.end(), time,
                                      [](const TimedPose& p, double t) { return p.time < t; });
  if (after->time == time) return after->pose;
  return interpolatePose(*(after - 1), *after, time);
}

}  // namespace uampc::evaluator
