// The adaptive process noise (adaptive_process_noise.hpp) and the Cauchy kernel's weights
// (normal_equations.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "uampc/lo/adaptive_process_noise.hpp"
#include "uampc/lo/normal_equations.hpp"

namespace uampc::lo {
namespace {

const ProcessNoise kFloor{0.001, 0.002};
const ProcessNoise kCeiling{0.1, 0.2};

TEST(AdaptiveProcessNoise, IsTheCeilingUntilHalfTheWindowIsSeen) {
  AdaptiveProcessNoise noise(1.0, kFloor, kCeiling);
  EXPECT_EQ(noise.estimate().linear, 0.1);
  for (int k = 1; k <= 4; ++k) noise.add(0.1 * k, 0.1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(noise.estimate().angular, 0.2);  // 0.4 s of 1 s
  noise.add(0.5, 0.1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(noise.estimate().linear, 0.001);  // still corrections: the floor
  EXPECT_EQ(noise.estimate().angular, 0.002);
}

TEST(AdaptiveProcessNoise, FollowsTheCorrectionsOfAnAcceleratingRig) {
  // A filter that trails a rig accelerating at a along one axis is corrected by about a dt per
  // update: q = (a dt)^2 / (3 dt) = a^2 dt / 3.
  AdaptiveProcessNoise noise(1.0, kFloor, {100.0, 100.0});
  const double a = 2.0, dt = 0.1;
  for (int k = 1; k <= 30; ++k) noise.add(dt * k, dt, {a * dt, 0.0, 0.0}, {0.0, 0.0, 0.5 * a * dt});
  EXPECT_NEAR(noise.estimate().linear, a * a * dt / 3.0, 1e-9);
  EXPECT_NEAR(noise.estimate().angular, 0.25 * a * a * dt / 3.0, 1e-9);
}

TEST(AdaptiveProcessNoise, ForgetsCorrectionsOlderThanTheWindowAndStaysWithinItsBounds) {
  AdaptiveProcessNoise noise(1.0, kFloor, kCeiling);
  for (int k = 1; k <= 10; ++k) noise.add(0.1 * k, 0.1, {5.0, 0.0, 0.0}, {5.0, 0.0, 0.0});
  EXPECT_EQ(noise.estimate().linear, 0.1);  // beyond the ceiling
  for (int k = 11; k <= 25; ++k) noise.add(0.1 * k, 0.1, {0.01, 0.0, 0.0}, Eigen::Vector3d::Zero());
  // Only the last second's small corrections: 1e-4 / (3 * 1.0) is below the floor.
  EXPECT_EQ(noise.estimate().linear, 0.001);
  EXPECT_EQ(noise.estimate().angular, 0.002);
}

TEST(AdaptiveProcessNoise, AFloorAboveItsCeilingGivesTheCeiling) {
  AdaptiveProcessNoise noise(0.2, {1.0, 1.0}, kCeiling);
  for (int k = 1; k <= 5; ++k) noise.add(0.1 * k, 0.1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(noise.estimate().linear, 0.1);
  EXPECT_EQ(noise.estimate().angular, 0.2);
}

TEST(CauchyKernel, WeighsAResidualOfItsScaleHalfAndIsOffAtZero) {
  EXPECT_DOUBLE_EQ(cauchyWeight(0.0, 0.05), 1.0);
  EXPECT_DOUBLE_EQ(cauchyWeight(0.05, 0.05), 0.5);
  EXPECT_DOUBLE_EQ(cauchyWeight(-0.15, 0.05), 0.1);
  EXPECT_DOUBLE_EQ(cauchyWeight(3.0, 0.0), 1.0);
}

TEST(CauchyKernel, TheNormalEquationsCarryTheWeights) {
  Linearisation plain;
  plain.rows.resize(2, 13);
  plain.rows.setZero();
  plain.z.resize(2);
  plain.z << 0.01, 0.2;
  for (int i = 0; i < 2; ++i) {
    plain.rows(i, 3) = 1.0;  // position x
    plain.rows(i, 12) = plain.z(i);
  }
  Linearisation weighted = plain;
  const NormalEquations n0 = normalEquations(plain, nullptr, std::numeric_limits<double>::infinity());
  const NormalEquations n1 = normalEquations(weighted, nullptr, std::numeric_limits<double>::infinity(), 0.05);
  EXPECT_DOUBLE_EQ(n0.HtH(3, 3), 2.0);
  EXPECT_NEAR(n1.HtH(3, 3), cauchyWeight(0.01, 0.05) + cauchyWeight(0.2, 0.05), 1e-12);
  EXPECT_NEAR(n1.Htz(3), cauchyWeight(0.01, 0.05) * 0.01 + cauchyWeight(0.2, 0.05) * 0.2, 1e-12);
  EXPECT_LT(n1.Htz(3), 0.5 * n0.Htz(3));  // the far residual's pull is cut most
}

}  // namespace
}  // namespace uampc::lo
