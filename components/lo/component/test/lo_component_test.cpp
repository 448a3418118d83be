// The adapter in-process: a scan waits for the encoder states covering it (and, with
// init_from_pose, for a start pose), then gives exactly one odometry, from the start pose and at
// the velocity differentiated from initial_pose.
#include <gtest/gtest.h>

#include <random>

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

// A scan from inside a 20 m x 16 m x 6 m room: random points on its six walls, times spread over
// 0.1 s from the stamp.
sensor_msgs::msg::PointCloud2 roomScan(double stamp) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const Eigen::Vector3f half(10.0f, 8.0f, 3.0f);
  pointcloud::ScanPoints points;
  for (int i = 0; i < 3000; ++i) {
    Eigen::Vector3f p(unit(random) * half.x(), unit(random) * half.y(), unit(random) * half.z());
    const int axis = i % 3;
    p[axis] = (i / 3) % 2 ? half[axis] : -half[axis];
    points.positions.push_back(p);
    points.intensities.push_back(1.0f);
    points.time_offsets.push_back(0.1f * static_cast<float>(i) / 3000.0f);
    points.rings.push_back(0);
  }
  auto cloud = pointcloud::makeScanCloud(points, "lidar");
  cloud.header().stamp(toMsg(Time::fromSeconds(stamp)));
  return cloud;
}

sensor_msgs::msg::JointState encoderState(double t) {
  sensor_msgs::msg::JointState s;
  s.header().stamp(toMsg(Time::fromSeconds(t)));
  s.position({0.0});
  s.velocity({0.0});
  return s;
}

geometry_msgs::msg::PoseStamped poseSample(double t, double x) {
  geometry_msgs::msg::PoseStamped p;
  p.header().stamp(toMsg(Time::fromSeconds(t)));
  p.pose().position().x(x);
  p.pose().orientation().w(1.0);
  return p;
}

void injectEncoderStates(testing::TestContext& ctx, int from_step, int to_step) {
  for (int k = from_step; k <= to_step; ++k) ctx.inject("motor_state", encoderState(0.005 * k));
}

TEST(LoComponent, WaitsForEncoderStatesCoveringTheScanThenPublishesOneOdometry) {
  testing::TestContext ctx("lo", {{"init_from_pose", "false"}});
  injectEncoderStates(ctx, 180, 200);  // 0.9 .. 1.0 s
  ctx.inject("scan", roomScan(1.0));
  injectEncoderStates(ctx, 201, 219);  // up to 1.095 s: the scan's last point (1.1 s) not covered
  EXPECT_EQ(ctx.publishedCount("odometry"), 0u);
  injectEncoderStates(ctx, 220, 222);
  const auto odometry = ctx.published<nav_msgs::msg::Odometry>("odometry");
  ASSERT_EQ(odometry.size(), 1u);
  const double last_point = 1.0 + 0.1f * 2999.0f / 3000.0f;
  EXPECT_NEAR(fromMsg(odometry[0].header().stamp()).seconds(), last_point, 1e-6);  // the scan's end
  EXPECT_EQ(odometry[0].child_frame_id(), "base_link");
  EXPECT_EQ(odometry[0].pose().pose().position().x(), 0.0);  // identity: init_from_pose false
  EXPECT_EQ(ctx.publishedCount("registered"), 1u);
  EXPECT_EQ(ctx.publishedCount("metrics"), 1u);
}

TEST(LoComponent, StartsFromInitialPoseWithItsVelocity) {
  testing::TestContext ctx("lo");  // init_from_pose: true
  injectEncoderStates(ctx, 180, 230);
  ctx.inject("scan", roomScan(1.0));
  EXPECT_EQ(ctx.publishedCount("odometry"), 0u);  // covered, but no start pose yet
  // 2 m/s along x: samples every 0.05 s, the first at or after the scan's end (1.1 s) is at 1.1.
  for (int k = 0; k <= 24; ++k) ctx.inject("initial_pose", poseSample(0.05 * k, 0.1 * k));
  ctx.inject("motor_state", encoderState(1.155));
  const auto odometry = ctx.published<nav_msgs::msg::Odometry>("odometry");
  ASSERT_EQ(odometry.size(), 1u);
  EXPECT_NEAR(odometry[0].pose().pose().position().x(), 2.2, 1e-3);
  EXPECT_NEAR(odometry[0].twist().twist().linear().x(), 2.0, 0.05);
  // The covariance is in ROS order: a variance on the diagonal of both blocks.
  for (int i = 0; i < 6; ++i) EXPECT_GT(odometry[0].pose().covariance()[7 * i], 0.0) << i;
}

sensor_msgs::msg::Imu imuAtRest(double t, double gravity) {
  sensor_msgs::msg::Imu m;
  m.header().stamp(toMsg(Time::fromSeconds(t)));
  m.linear_acceleration().z(gravity);
  return m;
}

// m/s^2 per unit of the IMU's acceleration, as the LO's metrics say with its first odometry.
double accelerationScaleAfterAScan(const std::string& unit, double gravity) {
  testing::TestContext ctx("lo", {{"init_from_pose", "false"}, {"use_imu", "true"}, {"imu_acceleration_unit", unit}});
  for (int k = 0; k <= 240; ++k) ctx.inject("imu", imuAtRest(0.9 + 0.005 * k, gravity));  // 200 Hz to 2.1 s
  injectEncoderStates(ctx, 180, 230);
  ctx.inject("scan", roomScan(1.0));
  const auto metrics = ctx.published<msg::Metrics>("metrics");
  if (metrics.size() != 1u) return -1.0;
  for (const auto& v : metrics[0].values()) {
    if (v.name() == "imu_acceleration_scale") return v.value();
  }
  return 0.0;
}

// livox_ros_driver2 publishes the Mid-360's acceleration in g: read as m/s^2 an IMU at rest would
// say the rig falls at 8.8 m/s^2. auto tells the two apart by the readings' mean.
TEST(LoComponent, TellsAnImuInGFromOneInMetresPerSecondSquared) {
  EXPECT_DOUBLE_EQ(accelerationScaleAfterAScan("auto", 1.0), 9.80665);
  EXPECT_DOUBLE_EQ(accelerationScaleAfterAScan("auto", 9.81), 1.0);
  EXPECT_DOUBLE_EQ(accelerationScaleAfterAScan("g", 9.81), 9.80665);  // told: not guessed
  EXPECT_DOUBLE_EQ(accelerationScaleAfterAScan("m/s^2", 1.0), 1.0);
  EXPECT_DOUBLE_EQ(accelerationScaleAfterAScan("auto", 4.0), 1.0);  // neither: as sensor_msgs says
}

}  // namespace
}  // namespace uampc
