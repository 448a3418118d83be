#include "uampc/world/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace uampc::world {

AttitudeMode attitudeModeFromName(const std::string& name) {
  if (name == "from_file") return AttitudeMode::kFromFile;
  if (name == "yaw_only") return AttitudeMode::kYawOnly;
  if (name == "identity") return AttitudeMode::kIdentity;
  throw std::invalid_argument("unknown attitude mode '" + name +
                              "' (expected from_file, yaw_only or identity)");
}

Trajectory::Trajectory(std::vector<TimedPose> poses) : poses_(std::move(poses)) {
  if (poses_.empty()) throw std::invalid_argument("Trajectory: no poses");
  for (std::size_t i = 0; i < poses_.size(); ++i) {
    if (i > 0 && !(poses_[i].time > poses_[i - 1].time)) {
      std::ostringstream msg;
      msg << "Trajectory: time of pose " << i << " (" << poses_[i].time
          << " s) is not after the previous one (" << poses_[i - 1].time << " s)";
      throw std::invalid_argument(msg.str());
    }
    poses_[i].orientation.normalize();
  }
}

bool Trajectory::contains(double t) const {
  return !poses_.empty() && t >= startTime() && t <= endTime();
}

Eigen::Isometry3d Trajectory::poseAt(double t) const {
  if (!contains(t)) {
    std::ostringstream msg;
    msg.precision(17);
    msg << "Trajectory: time " << t << " s outside [" << (poses_.empty() ? 0.0 : startTime())
        << ", " << (poses_.empty() ? 0.0 : endTime()) << "] s";
    throw std::out_of_range(msg.str());
  }
  // First sample strictly after t; the one before it is at or before t.
  auto after = std::upper_bound(poses_.begin(), poses_.end(), t,
                                [](double time, const TimedPose& p) { return time < p.time; });
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (after == poses_.end()) {  // t == endTime()
    T.linear() = poses_.back().orientation.toRotationMatrix();
    T.translation() = poses_.back().position;
    return T;
  }
  const TimedPose& a = *std::prev(after);
  const TimedPose& b = *after;
  const double s = (t - a.time) / (b.time - a.time);
  T.linear() = a.orientation.slerp(s, b.orientation).toRotationMatrix();
  T.translation() = (1.0 - s) * a.position + s * b.position;
  return T;
}

Trajectory Trajectory::shiftedInTime(double offset) const {
  std::vector<TimedPose> shifted = poses_;
  for (auto& p : shifted) p.time += offset;
  return Trajectory(std::move(shifted));
}

Eigen::Quaterniond yawOnly(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
  // A body looking straight up or down has no heading; keep the heading of its y axis then.
  const double yaw =
      (std::hypot(x.x(), x.y()) > 1e-9)
          ? std::atan2(x.y(), x.x())
          : std::atan2((q * Eigen::Vector3d::UnitY()).y(), (q * Eigen::Vector3d::UnitY()).x()) -
                M_PI / 2;
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

void applyAttitudeMode(std::vector<TimedPose>& poses, AttitudeMode mode,
                       const Eigen::Quaterniond& correction) {
  for (auto& p : poses) {
    switch (mode) {
      case AttitudeMode::kFromFile:
        p.orientation = (p.orientation * correction).normalized();
        break;
      case AttitudeMode::kYawOnly:
        p.orientation = yawOnly(p.orientation * correction);
        break;
      case AttitudeMode::kIdentity:
        p.orientation = Eigen::Quaterniond::Identity();
        break;
    }
  }
}

}  // namespace uampc::world
