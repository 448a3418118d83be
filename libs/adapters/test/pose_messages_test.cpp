#include <gtest/gtest.h>

#include "uampc/adapters/pose_messages.hpp"

namespace uampc::adapters {
namespace {

TEST(PoseMessages, PositionFirstMovesTheRotationBlockBehindThePosition) {
  // Entry (i, j) encodes its indices, so every move can be checked.
  Matrix6d rotation_first;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) rotation_first(i, j) = 10 * i + j;
  }
  const Matrix6d ros = positionFirst(rotation_first);
  const int from[6] = {3, 4, 5, 0, 1, 2};
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) EXPECT_EQ(ros(i, j), 10 * from[i] + from[j]) << i << "," << j;
  }
  // Variance of x (filter index 3) first; rotation-position correlation lands off the diagonal blocks.
  EXPECT_EQ(ros(0, 0), 33);
  EXPECT_EQ(ros(0, 3), 30);
}

TEST(PoseMessages, OdometryMessageCarriesPoseTwistAndCovariancesRowMajor) {
  BaseOdometry odometry;
  odometry.stamp = Time{12'500'000'000};
  odometry.T_WB.translation() = Eigen::Vector3d(1, 2, 3);
  odometry.T_WB.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  odometry.linear_velocity_B = Eigen::Vector3d(0.1, 0.2, 0.3);
  odometry.angular_velocity_B = Eigen::Vector3d(0.4, 0.5, 0.6);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      odometry.pose_covariance(i, j) = 10 * i + j;
      odometry.twist_covariance(i, j) = 100 + 10 * i + j;
    }
  }
  const nav_msgs::msg::Odometry o = toOdometryMessage(odometry);
  EXPECT_EQ(fromMsg(o.header().stamp()), odometry.stamp);
  EXPECT_EQ(o.header().frame_id(), "odom");
  EXPECT_EQ(o.child_frame_id(), "base_link");
  EXPECT_TRUE(toIsometry(o.pose().pose()).isApprox(odometry.T_WB, 1e-12));
  EXPECT_EQ(o.twist().twist().linear().y(), 0.2);
  EXPECT_EQ(o.twist().twist().angular().z(), 0.6);
  EXPECT_EQ(o.pose().covariance()[6 * 1 + 4], 14);  // row 1, column 4
  EXPECT_EQ(o.twist().covariance()[6 * 5 + 0], 150);
}

}  // namespace
}  // namespace uampc::adapters
