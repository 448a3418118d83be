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

nav_msgs::msg::Odometry toOdometryMessage(const BaseOdometry& odometry) {
  nav_msgs::msg::Odometry o;
  o.header().stamp(toMsg(odometry.stamp));
  o.header().frame_id("odom");
  o.child_frame_id("base_link");
  o.pose().pose(toPoseMessage(odometry.T_WB));
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      o.pose().covariance()[6 * i + j] = odometry.pose_covariance(i, j);
      o.twist().covariance()[6 * i + j] = odometry.twist_covariance(i, j);
    }
  }
  const Eigen::Vector3d& v = odometry.linear_velocity_B;
  const Eigen::Vector3d& w = odometry.angular_velocity_B;
  o.twist().twist().linear().x(v.x());
  o.twist().twist().linear().y(v.y());
  o.twist().twist().linear().z(v.z());
  o.twist().twist().angular().x(w.x());
  o.twist().twist().angular().y(w.y());
  o.twist().twist().angular().z(w.z());
  return o;
}

Matrix6d positionFirst(const Matrix6d& rotation_first) {
  // Row/column i of the result is row/column kFrom[i] of the input.
  static constexpr int kFrom[6] = {3, 4, 5, 0, 1, 2};
  Matrix6d out;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) out(i, j) = rotation_first(kFrom[i], kFrom[j]);
  }
  return out;
}

}  // namespace uampc::adapters
