// The adapter in-process: without a pose and a local map the controller commands omega_pre and
// plans nothing; with them it plans (U samples, a horizon) and publishes the panorama.
#include <gtest/gtest.h>

#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

// Points every 0.5 m on the walls of a 20 m x 12 m room, 4 m high, around the origin.
sensor_msgs::msg::PointCloud2 roomMap() {
  std::vector<Eigen::Vector3f> points;
  for (float z = 0.0f; z <= 4.0f; z += 0.5f) {
    for (float x = -10.0f; x <= 10.0f; x += 0.5f) {
      points.emplace_back(x, -6.0f, z);
      points.emplace_back(x, 6.0f, z);
    }
    for (float y = -6.0f; y <= 6.0f; y += 0.5f) {
      points.emplace_back(-10.0f, y, z);
      points.emplace_back(10.0f, y, z);
    }
  }
  return pointcloud::makeXyzCloud(points, "map");
}

nav_msgs::msg::Odometry atOrigin() {
  nav_msgs::msg::Odometry o;
  o.pose().pose().position().z(1.0);
  o.pose().pose().orientation().w(1.0);
  return o;
}

TEST(MpcComponent, CommandsOmegaPreUntilItHasAPoseAndAMapThenPlans) {
  testing::TestContext ctx("mpc", {{"rate", "10"}});
  const double omega_pre = ctx.paramDouble("omega_pre");
  ctx.advanceTo(Time{0});
  ASSERT_EQ(ctx.publishedCount("command"), 1u);
  EXPECT_EQ(ctx.published<msg::MotorCommand>("command")[0].velocity(), omega_pre);
  EXPECT_TRUE(ctx.published<msg::UncertaintyProfile>("profile")[0].samples().empty());
  EXPECT_EQ(ctx.publishedCount("panorama"), 0u);

  ctx.inject("odometry", atOrigin());
  ctx.inject("local_map", roomMap());
  ctx.advanceTo(Time::fromSeconds(0.1));
  const auto commands = ctx.published<msg::MotorCommand>("command");
  const auto profiles = ctx.published<msg::UncertaintyProfile>("profile");
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_GE(commands[1].velocity(), ctx.paramDouble("omega_min"));
  EXPECT_LE(commands[1].velocity(), ctx.paramDouble("omega_max"));
  EXPECT_FALSE(profiles[1].samples().empty());
  EXPECT_EQ(profiles[1].horizon_omega().size(), static_cast<std::size_t>(ctx.paramInt("horizon") + 1));
  EXPECT_EQ(profiles[1].command(), commands[1].velocity());
  ASSERT_EQ(ctx.publishedCount("panorama"), 1u);
  const auto panorama = ctx.published<sensor_msgs::msg::Image>("panorama")[0];
  EXPECT_EQ(panorama.width(), static_cast<std::uint32_t>(ctx.paramInt("panorama_width")));
  EXPECT_EQ(ctx.publishedCount("timing"), 2u);
}

TEST(MpcComponent, AStaleMapSendsItBackToOmegaPre) {
  testing::TestContext ctx("mpc", {{"rate", "10"}, {"stale_after", "0.25"}});
  ctx.inject("odometry", atOrigin());
  ctx.inject("local_map", roomMap());
  ctx.advanceTo(Time::fromSeconds(0.5));  // planned at 0, 0.1, 0.2; stale from 0.3 on
  const auto profiles = ctx.published<msg::UncertaintyProfile>("profile");
  ASSERT_EQ(profiles.size(), 6u);
  EXPECT_FALSE(profiles[2].samples().empty());
  EXPECT_TRUE(profiles[3].samples().empty());
  EXPECT_EQ(ctx.published<msg::MotorCommand>("command").back().velocity(), ctx.paramDouble("omega_pre"));
}

}  // namespace
}  // namespace uampc
