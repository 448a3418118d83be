// stableSubset: a budget that gives half its points to the directions the scan constrains least.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>
#include <random>

#include "uampc/lo/stable_sample.hpp"
#include "uampc/lo/voxel_downsample.hpp"

namespace uampc::lo {
namespace {

// A plane's points on a 0.1 m grid: origin + i u + j v.
void addPatch(std::vector<TimedPoint>& raw, const Eigen::Vector3d& origin, const Eigen::Vector3d& u, int nu,
              const Eigen::Vector3d& v, int nv) {
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) raw.push_back({origin + 0.1 * i * u + 0.1 * j * v, -1e-6 * static_cast<double>(raw.size())});
  }
}

// A corridor 30 m long along x, 6 m wide and 4 m high (walls at y = +-3 m, floor and ceiling), and one small patch
// across it (1 m x 1 m at x = 6.05 m, off the walls' grid, its normal along the axis): the only thing that holds the
// position along the axis.
std::vector<TimedPoint> corridorWithOnePatch() {
  std::vector<TimedPoint> raw;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  for (const double wall : {-3.0, 3.0}) addPatch(raw, {-15.0, wall, -1.5}, x, 300, z, 40);
  for (const double level : {-1.5, 2.5}) addPatch(raw, {-15.0, -3.0, level}, x, 300, y, 60);
  addPatch(raw, {6.05, -0.5, 0.0}, y, 10, z, 10);
  return raw;
}

bool onPatch(const TimedPoint& p) { return std::abs(p.p_B.x() - 6.05) < 1e-9; }

std::size_t countOnPatch(const std::vector<TimedPoint>& points) {
  return static_cast<std::size_t>(std::count_if(points.begin(), points.end(), onPatch));
}

// The smallest eigenvalue of a sample's pose information, with the corridor's true normals, in
// the units of the LO's degeneracy analysis (rotation at a 10 m lever arm).
double weakestInformation(const std::vector<TimedPoint>& sample) {
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  for (const TimedPoint& point : sample) {
    const Eigen::Vector3d& p = point.p_B;
    const Eigen::Vector3d n = onPatch(point)                   ? Eigen::Vector3d::UnitX()
                              : std::abs(std::abs(p.y()) - 3.0) < 1e-9 ? Eigen::Vector3d::UnitY()
                                                                      : Eigen::Vector3d::UnitZ();
    Eigen::Matrix<double, 6, 1> row;
    row << p.cross(n) / 10.0, n;
    information += row * row.transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(information).eigenvalues()(0);
}

TEST(StableSubset, GivesTheWeakDirectionThePointsThatHoldIt) {
  const std::vector<TimedPoint> raw = corridorWithOnePatch();
  const std::vector<TimedPoint> downsampled = voxelDownsample(raw, 0.3);
  const std::size_t patch = countOnPatch(downsampled);
  ASSERT_GE(patch, 9u);
  const std::size_t budget = 400;  // about a tenth of the scan
  const std::vector<TimedPoint> even = spatialSubset(downsampled, budget, 0.3);
  const std::vector<TimedPoint> stable = stableSubset(downsampled, raw, budget, StableSampleOptions{});
  ASSERT_EQ(stable.size(), budget);
  // The even sample keeps the patch's share (about a tenth); the stable one several times more,
  // and its weakest direction (along the axis) is held several times better.
  const double even_weakest = weakestInformation(even), stable_weakest = weakestInformation(stable);
  std::printf("patch points %zu of %zu: even sample %zu, stable %zu; weakest information %.2f against %.2f\n",
              countOnPatch(even), patch, countOnPatch(even), countOnPatch(stable), even_weakest, stable_weakest);
  EXPECT_LE(countOnPatch(even), patch / 5);
  EXPECT_GE(countOnPatch(stable), 3 * countOnPatch(even));
  EXPECT_GT(stable_weakest, 3.0 * even_weakest);
  // Every point kept is one of the scan's, with its time.
  for (const TimedPoint& kept : stable) {
    const auto same = [&kept](const TimedPoint& p) { return p.p_B == kept.p_B && p.tau == kept.tau; };
    EXPECT_NE(std::find_if(downsampled.begin(), downsampled.end(), same), downsampled.end());
  }
  // Deterministic: the same scan gives the same sample.
  const std::vector<TimedPoint> again = stableSubset(downsampled, raw, budget, StableSampleOptions{});
  ASSERT_EQ(again.size(), stable.size());
  for (std::size_t i = 0; i < again.size(); ++i) EXPECT_EQ(again[i].p_B, stable[i].p_B);
}

TEST(StableSubset, WithinTheBudgetOrWithoutPlanesItIsTheEvenSample) {
  const std::vector<TimedPoint> raw = corridorWithOnePatch();
  const std::vector<TimedPoint> downsampled = voxelDownsample(raw, 0.3);
  EXPECT_EQ(stableSubset(downsampled, raw, 0, StableSampleOptions{}).size(), downsampled.size());
  EXPECT_EQ(stableSubset(downsampled, raw, downsampled.size(), StableSampleOptions{}).back().p_B, downsampled.back().p_B);

  // Points scattered in a volume: no cell holds a plane, so no point has a normal.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::vector<TimedPoint> cloud;
  for (int i = 0; i < 3000; ++i) cloud.push_back({{coordinate(random), coordinate(random), coordinate(random)}, 0.0});
  const std::vector<TimedPoint> stable = stableSubset(cloud, cloud, 300, StableSampleOptions{});
  const std::vector<TimedPoint> even = spatialSubset(cloud, 300, 0.3);
  ASSERT_EQ(stable.size(), even.size());
  for (std::size_t i = 0; i < even.size(); ++i) EXPECT_EQ(stable[i].p_B, even[i].p_B);
}

}  // namespace
}  // namespace uampc::lo
