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

Interpolation interpolationFromName(const std::string& name) {
  if (name == "linear") return Interpolation::kLinear;
  if (name == "smooth") return Interpolation::kSmooth;
  throw std::invalid_argument("unknown interpolation '" + name + "' (expected linear or smooth)");
}

namespace {

// Quaternion logarithm and exponential (pure quaternions as 3-vectors): log(q) = axis * angle / 2.
Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q) {
  const Eigen::AngleAxisd aa(q);
  return aa.axis() * (0.5 * aa.angle());
}
Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& v) {
  const double half_angle = v.norm();
  if (half_angle < 1e-12) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(2.0 * half_angle, v / half_angle));
}
// q2 in the hemisphere of q1, so that interpolation takes the short way.
Eigen::Quaterniond near(const Eigen::Quaterniond& q1, const Eigen::Quaterniond& q2) {
  return q1.dot(q2) < 0 ? Eigen::Quaterniond(-q2.coeffs()) : q2;
}
// SQUAD's inner control point at q with neighbours before and after.
Eigen::Quaterniond squadControl(const Eigen::Quaterniond& before, const Eigen::Quaterniond& q,
                                const Eigen::Quaterniond& after) {
  const Eigen::Quaterniond inverse = q.conjugate();
  const Eigen::Vector3d sum = quaternionLog(inverse * near(q, after)) + quaternionLog(inverse * near(q, before));
  return q * quaternionExp(-0.25 * sum);
}

}  // namespace

Trajectory::Trajectory(std::vector<TimedPose> poses, Interpolation interpolation)
    : poses_(std::move(poses)), interpolation_(interpolation) {
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
  if (interpolation_ == Interpolation::kLinear) {
    T.linear() = a.orientation.slerp(s, b.orientation).toRotationMatrix();
    T.translation() = (1.0 - s) * a.position + s * b.position;
    return T;
  }
  // Smooth: the neighbours before a and after b (the ends repeat themselves).
  const TimedPose& before = std::prev(after) == poses_.begin() ? a : *std::prev(after, 2);
  const TimedPose& next = std::next(after) == poses_.end() ? b : *std::next(after);
  // Cubic Hermite in position with Catmull-Rom tangents (finite differences over the neighbours).
  const double h = b.time - a.time;
  const Eigen::Vector3d m_a = (b.position - before.position) / std::max(b.time - before.time, 1e-9);
  const Eigen::Vector3d m_b = (next.position - a.position) / std::max(next.time - a.time, 1e-9);
  const double s2 = s * s, s3 = s2 * s;
  T.translation() = (2 * s3 - 3 * s2 + 1) * a.position + (s3 - 2 * s2 + s) * h * m_a +
                    (-2 * s3 + 3 * s2) * b.position + (s3 - s2) * h * m_b;
  // SQUAD in attitude: slerp of slerps through control points built from the neighbours.
  const Eigen::Quaterniond qa = a.orientation;
  const Eigen::Quaterniond qb = near(qa, b.orientation);
  const Eigen::Quaterniond sa = squadControl(before.orientation, qa, qb);
  const Eigen::Quaterniond sb = squadControl(qa, qb, near(qb, next.orientation));
  const Eigen::Quaterniond q = qa.slerp(s, qb).slerp(2 * s * (1 - s), sa.slerp(s, near(sa, sb)));
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

Trajectory movingAverage(const Trajectory& trajectory, double window) {
  const auto& poses = trajectory.poses();
  std::vector<TimedPose> out;
  out.reserve(poses.size());
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    while (poses[lo].time < poses[i].time - 0.5 * window) ++lo;
    while (hi + 1 < poses.size() && poses[hi + 1].time <= poses[i].time + 0.5 * window) ++hi;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector4d q = Eigen::Vector4d::Zero();
    for (std::size_t k = lo; k <= hi; ++k) {
      position += poses[k].position;
      const Eigen::Vector4d c = poses[k].orientation.coeffs();
      q += c.dot(poses[i].orientation.coeffs()) < 0 ? Eigen::Vector4d(-c) : c;
    }
    out.push_back({poses[i].time, position / static_cast<double>(hi - lo + 1), Eigen::Quaterniond(q.normalized())});
  }
  return Trajectory(std::move(out), trajectory.interpolation());
}

Trajectory Trajectory::shiftedInTime(double offset) const {
  std::vector<TimedPose> shifted = poses_;
  for (auto& p : shifted) p.time += offset;
  return Trajectory(std::move(shifted), interpolation_);
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

Trajectory withHeldStart(const Trajectory& trajectory, double hold, double ease) {
  if (!(hold > 0.0)) return trajectory;
  if (!(ease > 0.0)) throw std::invalid_argument("withHeldStart: the ease must take a positive time");
  const double start = trajectory.startTime();
  auto sampleAt = [&](double t_new, double tau) {
    const Eigen::Isometry3d T = trajectory.poseAt(std::min(start + tau, trajectory.endTime()));
    return TimedPose{t_new, T.translation(), Eigen::Quaterniond(T.linear())};
  };
  std::vector<TimedPose> poses{sampleAt(start, 0.0)};
  constexpr double kEaseSampleStep = 0.02;  // s
  const int ease_steps = static_cast<int>(std::ceil(ease / kEaseSampleStep));
  for (int k = 0; k <= ease_steps; ++k) {
    const double s = ease * k / ease_steps;  // s since the hold ended
    poses.push_back(sampleAt(start + hold + s, s * s / (2.0 * ease)));
  }
  const double delay = hold + ease / 2.0;
  for (const auto& p : trajectory.poses()) {
    if (p.time + delay > poses.back().time) poses.push_back({p.time + delay, p.position, p.orientation});
  }
  return Trajectory(std::move(poses), trajectory.interpolation());
}

}  // namespace uampc::world
