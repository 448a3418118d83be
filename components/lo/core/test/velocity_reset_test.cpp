// The LO's velocity resets (velocity_reset.hpp): the accepted poses' mean motion, the filter with
// its velocity replaced, and the LO resetting its velocity when it rejects an update for its speed
// or begins a loss of track, and saying so.
#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_world.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/lo/so3.hpp"
#include "uampc/lo/velocity_reset.hpp"

namespace uampc::lo {
namespace {

BaseState poseAt(const Eigen::Vector3d& r_WB, double yaw) {
  BaseState x;
  x.R_WB = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  x.r_WB = r_WB;
  return x;
}

TEST(AcceptedPoses, TheMeanMotionSpansTheWindow) {
  AcceptedPoses poses(1.0);
  EXPECT_FALSE(poses.meanMotion());
  // 2 m/s along x, turning at 0.5 rad/s, a pose every 0.1 s for 3 s.
  for (int k = 0; k <= 30; ++k) poses.add(0.1 * k, poseAt({0.2 * k, 0.0, 0.0}, 0.05 * k));
  const std::optional<Motion> motion = poses.meanMotion();
  ASSERT_TRUE(motion);
  EXPECT_NEAR(motion->v_W.x(), 2.0, 1e-9);
  EXPECT_NEAR(motion->v_W.tail<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(motion->w_B.z(), 0.5, 1e-9);
  // A wrong last second is not averaged with the older poses: the window is 1 s.
  for (int k = 31; k <= 40; ++k) poses.add(0.1 * k, poseAt({6.0, 0.0, 0.0}, 1.5));
  EXPECT_NEAR(poses.meanMotion()->v_W.norm(), 0.0, 1e-9);
}

TEST(AcceptedPoses, PosesCloserThanAFrameGiveNoMotion) {
  AcceptedPoses poses(1.0);
  poses.add(1.0, poseAt({0, 0, 0}, 0.0));
  poses.add(1.001, poseAt({1, 0, 0}, 0.0));
  EXPECT_FALSE(poses.meanMotion());
}

TEST(WithVelocity, ReplacesTheVelocityAndDropsItsCorrelations) {
  Matrix12d P = Matrix12d::Constant(0.01) + Matrix12d::Identity();
  const IteratedEkf filter(poseAt({1, 2, 3}, 0.3), P);
  Motion motion;
  motion.v_W = {1.0, 0.0, 0.0};
  motion.w_B = {0.0, 0.0, 0.2};
  const IteratedEkf kept = withVelocity(filter, motion, std::nullopt);
  EXPECT_EQ(kept.state().v_W, motion.v_W);
  EXPECT_EQ(kept.state().w_B, motion.w_B);
  EXPECT_EQ(kept.state().r_WB, filter.state().r_WB);
  EXPECT_TRUE((kept.covariance().topRightCorner<6, 6>().isZero()));
  EXPECT_TRUE((kept.covariance().bottomLeftCorner<6, 6>().isZero()));
  EXPECT_TRUE((kept.covariance().topLeftCorner<6, 6>() == P.topLeftCorner<6, 6>()));
  EXPECT_DOUBLE_EQ(kept.covariance()(6, 6), P(6, 6));
  EXPECT_DOUBLE_EQ(kept.covariance()(6, 7), 0.0);
  const IteratedEkf widened = withVelocity(filter, motion, 4.0);
  EXPECT_TRUE((widened.covariance().bottomRightCorner<6, 6>().isApprox(4.0 * Matrix6d::Identity())));
}

// The feature room, the rig weaving at 1 m/s.
struct RoomRun {
  sim::World world = sim::featureRoom();
  sim::LidarModel lidar;
  sim::Trajectory truth = sim::weavingTrajectory({0, 0, 1.2}, 1.0, 1.5, 1.0, 12.0);
  frames::MotorAngleTrack motor;

  OdometryResult frame(MotorizedLidarOdometry& odometry, int k, bool blind = false) {
    const double stamp = k * lidar.frame_duration;
    sim::feedMotor(motor, lidar, stamp, stamp + lidar.frame_duration);
    sim::SimulatedScan simulated = sim::simulateScan(world, truth, lidar, stamp, k);
    if (blind) {  // every point beyond max_range: nothing to register, the frame keeps its end time
      for (auto& p : simulated.scan.points_L) p *= 1000.0f;
    }
    return odometry.registerScan(simulated.scan, motor);
  }
};

// An update that says the base moves faster than max_speed is refused, and the frame is predicted
// with the accepted poses' motion: the LO goes on at the speed the map agreed with, not at the
// speed it refused.
TEST(MotorizedLidarOdometry, AnUpdateBeyondTheSpeedLimitIsRefusedAndTheVelocityReset) {
  RoomRun run;
  OdometryConfig config;
  config.initial_pose = run.truth(0.0);
  config.max_speed = 0.8;  // the rig reaches 1 m/s at 1.7 s
  MotorizedLidarOdometry odometry(config);
  std::size_t refused = 0;
  OdometryResult result;
  for (int k = 0; k < 30; ++k) {
    result = run.frame(odometry, k);
    if (result.implausible_motion) {
      ++refused;
      EXPECT_TRUE(result.velocity_reset) << "frame " << k;
      EXPECT_NE(result.warning.find("velocity reset"), std::string::npos) << result.warning;
      EXPECT_LE(result.linear_velocity_W.norm(), config.max_speed + 1e-6) << "frame " << k;
    }
  }
  EXPECT_GT(refused, 0u);
  // Every refusal reset the velocity; refused for over lost_after, the loss began with one more.
  EXPECT_GE(result.velocity_resets, refused);
  EXPECT_LE(result.velocity_resets, refused + 1);
}

// A loss of track (1.5 s without a usable point) begins with the LO going back to its last
// accepted pose and carrying it on with the accepted poses' motion, once; when the scans come back
// it registers again.
TEST(MotorizedLidarOdometry, ALossBeginsWithAVelocityResetAndTheLoRegistersAgain) {
  RoomRun run;
  OdometryConfig config;
  config.initial_pose = run.truth(0.0);
  MotorizedLidarOdometry odometry(config);
  for (int k = 0; k < 30; ++k) ASSERT_FALSE(run.frame(odometry, k).velocity_reset) << "frame " << k;
  int resets = 0;
  OdometryResult result;
  for (int k = 30; k < 45; ++k) {
    result = run.frame(odometry, k, /*blind=*/true);
    if (result.velocity_reset) {
      ++resets;
      EXPECT_TRUE(result.lost);
      EXPECT_NE(result.warning.find("lost track: going on from the last accepted pose"), std::string::npos)
          << result.warning;
      // The motion of the last second, which the map agreed with: the true speed within a few cm/s.
      const Eigen::Vector3d v_true =
          (run.truth(result.time).translation() - run.truth(result.time - 0.01).translation()) / 0.01;
      EXPECT_NEAR(result.linear_velocity_W.norm(), v_true.norm(), 0.1);
    }
  }
  EXPECT_EQ(resets, 1);
  EXPECT_EQ(result.velocity_resets, 1u);
  for (int k = 45; k < 55; ++k) result = run.frame(odometry, k);
  EXPECT_EQ(result.status, OdometryStatus::kTracking) << result.warning;
  EXPECT_LT((run.truth(result.time).translation() - result.T_WB.translation()).norm(), 0.1);
}

}  // namespace
}  // namespace uampc::lo
