#include "uampc/adapters/pose_messages.hpp"

#include <cmath>

namespace uampc::adapters {

Eigen::Isometry3d toIsometry(const geometry_msgs::msg::Pose& pose) {
  const auto& q = pose.orientation();
  const auto& p = pose.position();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.x(), p.y(), p.z());
  return T;
}

geometry_msgs::msg::Pose toPoseMessage(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  geometry_msgs::msg::Pose pose;
  pose.position().x(T.translation().x());
  pose.position().y(T.translation().y());
  pose.position().z(T.translation().z());
  pose.orientation().x(q.x());
  pose.orientation().y(q.y());
  pose.orientation().z(q.z());
  pose.orientation().w(q.w());
  return pose;
}

bool isFinitePose(const geometry_msgs::msg::Pose& pose) {
  const auto& q = pose.orientation();
  const auto& p = pose.position();
  const double norm = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w());
  return std::isfinite(p.x() + p.y() + p.z()) && std::isfinite(norm) && norm > 1e-6;
}

}  // namespace uampc::adapters
