// geometry_msgs/Pose <-> Eigen, in one place.
#pragma once

#include <Eigen/Geometry>

#include "geometry_msgs/msg/Pose.h"

namespace uampc::adapters {

// The pose as T_WB. The quaternion is normalised; a zero or non-finite one gives a non-finite
// matrix, which callers check with isFinitePose.
Eigen::Isometry3d toIsometry(const geometry_msgs::msg::Pose& pose);
geometry_msgs::msg::Pose toPoseMessage(const Eigen::Isometry3d& T);
// Finite position and a quaternion of non-zero, finite norm.
bool isFinitePose(const geometry_msgs::msg::Pose& pose);

}  // namespace uampc::adapters
