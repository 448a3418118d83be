// geometry_msgs/Pose and nav_msgs/Odometry <-> Eigen, in one place.
#pragma once

#include <Eigen/Geometry>

#include "geometry_msgs/msg/Pose.h"
#include "nav_msgs/msg/Odometry.h"
#include "uampc/runtime/time.hpp"

namespace uampc::adapters {

// The pose as T_WB. The quaternion is normalised; a zero or non-finite one gives a non-finite
// matrix, which callers check with isFinitePose.
Eigen::Isometry3d toIsometry(const geometry_msgs::msg::Pose& pose);
geometry_msgs::msg::Pose toPoseMessage(const Eigen::Isometry3d& T);
// Finite position and a quaternion of non-zero, finite norm.
bool isFinitePose(const geometry_msgs::msg::Pose& pose);

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The base's odometry as nav_msgs/Odometry lays it out: the twist in the base frame, the pose
// covariance ordered (x, y, z, rot x, rot y, rot z), the twist covariance (linear, angular).
struct BaseOdometry {
  Time stamp;
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d linear_velocity_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_B = Eigen::Vector3d::Zero();
  Matrix6d pose_covariance = Matrix6d::Zero();
  Matrix6d twist_covariance = Matrix6d::Zero();
};

// Frame ids "odom" (header) and "base_link" (child), REP-105's and the TF tree's (components/tf);
// covariances row-major, as ROS stores them.
nav_msgs::msg::Odometry toOdometryMessage(const BaseOdometry& odometry);

// A pose covariance ordered (rotation, position), as our filters keep it, in ROS's order
// (position, rotation).
Matrix6d positionFirst(const Matrix6d& rotation_first);

}  // namespace uampc::adapters
