#include "uampc/mpc/ua_mpc_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_scenes.hpp"

namespace uampc::mpc {
namespace {

Eigen::Isometry3d poseAt(double x, double yaw) {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_WB.translation() = Eigen::Vector3d(x, 0.0, 0.0);
  return T_WB;
}

test::Cloud corridorWithEndWall() {
  test::Cloud cloud = test::corridor(-40.0, 6.0);
  test::addEndWall(cloud, 6.0);
  return cloud;
}

TEST(UaMpcController, EmptyLocalMapReturnsPreferredSpeedWithFlag) {
  UaMpcController controller;
  const auto decision = controller.step(Eigen::Isometry3d::Identity(), {}, 1.0);
  EXPECT_TRUE(decision.local_map_empty);
  EXPECT_DOUBLE_EQ(decision.omega, 3.6);
  EXPECT_TRUE(decision.samples.empty());
  EXPECT_TRUE(decision.plan.speeds.empty());
  // Points that all fall outside the range window count as an empty map as well.
  const auto far = controller.step(Eigen::Isometry3d::Identity(), {{500.0, 0.0, 0.0}}, 1.0);
  EXPECT_TRUE(far.local_map_empty);
  EXPECT_DOUBLE_EQ(far.omega, 3.6);
}

TEST(UaMpcController, BaselineModes) {
  UaMpcController::Config config;
  config.mode = Mode::kConstant;
  config.constant_speed = 2.5;
  const test::Cloud cloud = corridorWithEndWall();
  auto constant = UaMpcController(config).step(Eigen::Isometry3d::Identity(), cloud, 0.0);
  EXPECT_DOUBLE_EQ(constant.omega, 2.5);
  EXPECT_TRUE(constant.samples.empty());
  config.mode = Mode::kZero;
  auto zero = UaMpcController(config).step(Eigen::Isometry3d::Identity(), cloud, 0.0);
  EXPECT_DOUBLE_EQ(zero.omega, 0.0);
  config.profile_in_baselines = true;
  auto profiled = UaMpcController(config).step(Eigen::Isometry3d::Identity(), cloud, 0.0);
  EXPECT_DOUBLE_EQ(profiled.omega, 0.0);
  EXPECT_EQ(profiled.samples.size(), 72U);
  EXPECT_TRUE(profiled.plan.speeds.empty());
}

TEST(UaMpcController, UaMpcStepIsConsistent) {
  UaMpcController controller;
  const test::Cloud cloud = corridorWithEndWall();
  const double theta_now = 12.0;  // multi-turn
  const auto decision = controller.step(poseAt(1.0, 0.3), cloud, theta_now);
  EXPECT_FALSE(decision.local_map_empty);
  ASSERT_EQ(decision.samples.size(), 72U);
  EXPECT_DOUBLE_EQ(decision.sample_start, theta_now);
  EXPECT_NEAR(decision.sample_step * 72, 2.0 * 3.14159265358979323846, 1e-12);
  for (double u : decision.samples) {
    EXPECT_TRUE(std::isfinite(u));
    EXPECT_GT(u, 0.0);
  }
  const auto& mpc = controller.config().mpc;
  ASSERT_EQ(decision.plan.speeds.size(), static_cast<std::size_t>(mpc.horizon + 1));
  EXPECT_DOUBLE_EQ(decision.omega, decision.plan.speeds.front());
  EXPECT_GE(decision.omega, mpc.omega_min);
  EXPECT_LE(decision.omega, mpc.omega_max);
  EXPECT_LE(decision.plan.cost, decision.plan.initial_cost);
  const PanoramicDepthMap::Config panorama;
  EXPECT_EQ(controller.depthMap().depthImage().size(), std::size_t(panorama.width * panorama.height));
  EXPECT_GE(decision.timings.total_ms, decision.timings.solve_ms);

  // Same map seen from a different yaw, with theta shifted by the same angle: the LiDAR looks in
  // the same world directions, so the profile is the same up to panorama discretisation.
  const auto turned = controller.step(poseAt(1.0, 0.3 + 0.5), cloud, theta_now - 0.5);
  int close = 0;
  for (int s = 0; s < 72; ++s) {
    close += std::abs(turned.samples[s] - decision.samples[s]) <= 0.2 * decision.samples[s];
  }
  EXPECT_GT(close, 60);
}

// The controller prefers a slow motor while the LiDAR faces the informative end wall and speeds
// up when it faces the open corridor: over a full turn of theta_now, the commands vary.
TEST(UaMpcController, CommandDependsOnWhereTheLidarLooks) {
  UaMpcController controller;
  const test::Cloud cloud = corridorWithEndWall();
  double slowest = 1e9;
  double fastest = -1e9;
  for (int s = 0; s < 24; ++s) {
    const double omega = controller.step(poseAt(0.0, 0.0), cloud, s * 2.0 * 3.14159265 / 24).omega;
    slowest = std::min(slowest, omega);
    fastest = std::max(fastest, omega);
  }
  EXPECT_GT(fastest - slowest, 1.0);
}

TEST(UaMpcController, ModeNames) {
  for (Mode mode : {Mode::kUaMpc, Mode::kConstant, Mode::kZero}) {
    EXPECT_EQ(parseMode(modeName(mode)), mode);
  }
  EXPECT_THROW(parseMode("fast"), std::invalid_argument);
}

}  // namespace
}  // namespace uampc::mpc
