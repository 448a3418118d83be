#include <gtest/gtest.h>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"

namespace uampc::frames {
namespace {

TEST(MotorizedLidar, ReferenceRigTiltsLidarZTowardsMinusY) {
  // Rotating about +x by 30 degrees takes the LiDAR z axis to (0, -sin30, cos30).
  const auto c = MotorLidarCalibration::referenceRig();
  const Eigen::Vector3d z = c.R_ML * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(z.x(), 0.0, 1e-12);
  EXPECT_NEAR(z.y(), -0.5, 1e-12);
  EXPECT_NEAR(z.z(), std::sqrt(3.0) / 2.0, 1e-12);
}

TEST(MotorizedLidar, Eq1ComposesMotorCalibrationAndBasePose) {
  MotorLidarCalibration c;
  c.r_ML = Eigen::Vector3d(0.1, 0, 0);
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.translation() = Eigen::Vector3d(10, 20, 30);
  // A point 1 m ahead on the LiDAR x axis, motor at 90 degrees: it ends up on the base +y axis.
  const Eigen::Vector3d p_W = lidarToWorld(Eigen::Vector3d(1, 0, 0), M_PI / 2, c, T_WB);
  EXPECT_TRUE(p_W.isApprox(Eigen::Vector3d(10, 21.1, 30), 1e-12)) << p_W.transpose();
  const Eigen::Isometry3d T_BL = lidarPoseInBase(M_PI / 2, c);
  EXPECT_TRUE((T_BL * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(0, 1.1, 0), 1e-12));
}

TEST(MotorAngleTrack, InterpolatesLinearlyInsideAndRefusesOutside) {
  MotorAngleTrack track;
  ASSERT_TRUE(track.add({0.0, 0.0, 1.0}));
  ASSERT_TRUE(track.add({0.1, 0.4, 4.0}));
  ASSERT_TRUE(track.add({0.2, 1.0, 6.0}));
  EXPECT_FALSE(track.add({0.2, 5.0, 0.0}));  // not newer
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.05), 0.2);
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.15), 0.7);
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.2), 1.0);
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.0), 0.0);
  EXPECT_FALSE(track.thetaAt(-0.01).has_value());
  EXPECT_FALSE(track.thetaAt(0.21).has_value());
  EXPECT_TRUE(track.covers(0.0, 0.2));
  EXPECT_FALSE(track.covers(0.0, 0.25));
}

TEST(MotorAngleTrack, DropsReadingsOlderThanTheWindow) {
  MotorAngleTrack track(1.0);
  for (int i = 0; i <= 300; ++i) track.add({i * 0.01, i * 0.036, 3.6});
  EXPECT_NEAR(track.oldest().time, 2.0, 1e-9);
  EXPECT_NEAR(track.newest().time, 3.0, 1e-9);
}

}  // namespace
}  // namespace uampc::frames
