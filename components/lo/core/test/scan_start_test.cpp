// The two decisions the lo component takes before the odometry sees a scan: whether the scan can
// be registered yet, and where the odometry starts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "uampc/lo/scan_readiness.hpp"
#include "uampc/lo/start_poses.hpp"

namespace uampc::lo {
namespace {

constexpr double kNoImu = std::numeric_limits<double>::infinity();

Scan scanFrom(double stamp, std::vector<float> offsets) {
  Scan scan;
  scan.stamp = stamp;
  scan.time_offsets = std::move(offsets);
  scan.points_L.assign(scan.time_offsets.size(), Eigen::Vector3f::Zero());
  return scan;
}

frames::MotorAngleTrack encoderStates(double from, double to, double period = 0.005) {
  frames::MotorAngleTrack motor(100.0);
  for (double t = from; t <= to + 1e-12; t += period) motor.add({t, t, 1.0});
  return motor;
}

TEST(ScanReadiness, EndIsTheLatestPointTime) {
  EXPECT_DOUBLE_EQ(scanEndTime(scanFrom(10.0, {0.0f, 0.08f, 0.05f})), 10.0 + 0.08f);
  EXPECT_DOUBLE_EQ(scanEndTime(scanFrom(10.0, {-0.1f})), 10.0);
  EXPECT_DOUBLE_EQ(scanEndTime(scanFrom(10.0, {})), 10.0);
}

TEST(ScanReadiness, WaitsUntilEncoderStatesCoverEveryPoint) {
  const Scan scan = scanFrom(1.0, {0.0f, 0.1f});
  EXPECT_FALSE(readyToRegister(scan, frames::MotorAngleTrack(), kNoImu, 0.5));
  EXPECT_FALSE(readyToRegister(scan, encoderStates(0.9, 1.05), kNoImu, 0.5));  // end not reached
  EXPECT_FALSE(readyToRegister(scan, encoderStates(1.02, 1.2), kNoImu, 0.5));  // start missed, not waited
  EXPECT_TRUE(readyToRegister(scan, encoderStates(0.9, 1.15), kNoImu, 0.5));
}

TEST(ScanReadiness, AGapInTheEncoderStatesIsWaitedForAtMostMaxMotorWait) {
  const Scan scan = scanFrom(1.0, {0.0f, 0.1f});
  const frames::MotorAngleTrack after_gap = encoderStates(1.05, 1.55);  // never covers the scan's start
  EXPECT_FALSE(readyToRegister(scan, after_gap, kNoImu, 0.5));          // 1.55 is not past 1.1 + 0.5
  EXPECT_TRUE(readyToRegister(scan, encoderStates(1.05, 1.65), kNoImu, 0.5));
}

TEST(ScanReadiness, LidarInertialModeAlsoWaitsForTheImu) {
  const Scan scan = scanFrom(1.0, {0.0f, 0.1f});
  const frames::MotorAngleTrack motor = encoderStates(0.9, 1.2);
  EXPECT_FALSE(readyToRegister(scan, motor, 1.09, 0.5));
  EXPECT_TRUE(readyToRegister(scan, motor, 1.1 + 1e-6, 0.5));
  // Waited long enough on the encoder: the scan goes without the IMU's end.
  EXPECT_TRUE(readyToRegister(scan, encoderStates(0.9, 1.7), 1.0, 0.5));
}

Eigen::Isometry3d poseAt(double x, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, 1.0, 2.0);
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

TEST(StartPoses, StartsAtTheFirstSampleAtOrAfterTheScanEndWithTheVelocityToIt) {
  StartPoses poses;
  // 2 m/s along x, yawing at 0.5 rad/s, sampled every 0.1 s.
  for (int k = 0; k <= 10; ++k) poses.add(0.1 * k, poseAt(0.2 * k, 0.05 * k));
  const std::optional<StartState> start = poses.at(0.43);
  ASSERT_TRUE(start);
  EXPECT_NEAR(start->T_WB.translation().x(), 1.0, 1e-12);  // the sample at 0.5 s, not the nearer 0.4 s
  EXPECT_TRUE(start->velocity_W.isApprox(Eigen::Vector3d(2.0, 0.0, 0.0), 1e-9)) << start->velocity_W;
  EXPECT_TRUE(start->angular_velocity_B.isApprox(Eigen::Vector3d(0.0, 0.0, 0.5), 1e-9)) << start->angular_velocity_B;
  // A sample within a nanosecond before the time counts as at it.
  EXPECT_NEAR(poses.at(0.5 + 5e-10)->T_WB.translation().x(), 1.0, 1e-12);
}

TEST(StartPoses, NothingUntilASampleWithOneBeforeItReachesTheTime) {
  StartPoses poses;
  EXPECT_FALSE(poses.at(0.0));
  poses.add(1.0, poseAt(0.0, 0.0));
  EXPECT_FALSE(poses.at(0.5));  // the only sample has none before it to give a velocity
  poses.add(1.1, poseAt(0.1, 0.0));
  EXPECT_FALSE(poses.at(1.2));
  ASSERT_TRUE(poses.at(0.5));
  EXPECT_NEAR(poses.at(0.5)->velocity_W.x(), 1.0, 1e-9);
}

TEST(StartPoses, SamplesSharingATimeGiveZeroVelocity) {
  StartPoses poses;
  poses.add(1.0, poseAt(0.0, 0.0));
  poses.add(1.0, poseAt(5.0, 1.0));
  const auto start = poses.at(1.0);
  ASSERT_TRUE(start);
  EXPECT_EQ(start->velocity_W, Eigen::Vector3d::Zero());
  EXPECT_EQ(start->angular_velocity_B, Eigen::Vector3d::Zero());
}

TEST(StartPoses, KeepsTheNewestSamplesOnly) {
  StartPoses poses;
  for (std::size_t k = 0; k < StartPoses::kCapacity + 10; ++k) {
    poses.add(static_cast<double>(k), poseAt(static_cast<double>(k), 0.0));
  }
  EXPECT_EQ(poses.size(), StartPoses::kCapacity);
  // Samples 0 to 9 are gone; sample 10, the oldest kept, has none before it: the start is 11.
  EXPECT_EQ(poses.at(0.0)->T_WB.translation().x(), 11.0);
  poses.clear();
  EXPECT_FALSE(poses.at(0.0));
}

}  // namespace
}  // namespace uampc::lo
