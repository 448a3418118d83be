// Tests of CMPLT: distinct voxels per window, bad input, and the OctoMap export.
#include "uampc/evaluator/completeness.hpp"

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include "test_directory.hpp"
#include "uampc/evaluator/voxel_octree.hpp"

namespace uampc::evaluator {
namespace {

constexpr float kFloatNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

using VoxelSet = std::set<std::tuple<int, int, int>>;

VoxelSet asSet(const std::vector<Eigen::Vector3i>& voxels) {
  VoxelSet set;
  for (const auto& v : voxels) set.emplace(v.x(), v.y(), v.z());
  return set;
}

// A point inside voxel v (0.5 m voxels).
Eigen::Vector3f in(int x, int y, int z) {
  return Eigen::Vector3f(x + 0.5f, y + 0.5f, z + 0.5f) * 0.5f;
}

TEST(Completeness, VoxelBoundariesAndNegativeCoordinates) {
  Completeness cmplt;
  cmplt.addScan(0.0, {{0.0f, 0.0f, 0.0f},  // voxel (0, 0, 0): a boundary belongs to the voxel above
                      {0.49f, 0.2f, 0.3f},     // (0, 0, 0)
                      {0.5f, 0.0f, 0.0f},      // (1, 0, 0)
                      {-0.01f, 0.0f, 0.0f},    // (-1, 0, 0): floor, not truncation toward zero
                      {-0.5f, 0.0f, 0.0f},     // (-1, 0, 0)
                      {-0.51f, 0.0f, 0.0f},    // (-2, 0, 0)
                      {0.25f, -0.25f, -1.0f},  // (0, -1, -2)
                      {1.0f, 1.0f, 1.0f}});    // (2, 2, 2)
  EXPECT_EQ(cmplt.totalVoxels(), 6u);
  const VoxelSet expected{{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {-2, 0, 0}, {0, -1, -2}, {2, 2, 2}};
  EXPECT_EQ(asSet(cmplt.voxels()), expected);
  const CompletenessReport report = cmplt.report();
  ASSERT_EQ(report.windows.size(), 1u);
  EXPECT_EQ(report.windows[0].voxels, 6u);
  EXPECT_EQ(report.windows[0].points, 8u);
}

// A wall exactly on a voxel face, posed exactly: rounding puts its points on both sides, and it
// counts as two layers of voxels. The grid offset moves the faces off it: one layer.
TEST(Completeness, AWallOnAVoxelFaceCountsOnceWithTheGridOffset) {
  std::vector<Eigen::Vector3f> wall;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> along(0.0f, 10.0f), rounding(-1e-6f, 1e-6f);
  for (int i = 0; i < 20000; ++i) wall.emplace_back(along(rng), 1.5f + rounding(rng), 0.5f * along(rng) / 2.0f);
  Completeness aligned;  // faces at multiples of 0.5 m: y = 1.5 is one
  aligned.addScan(0.0, wall);
  CompletenessConfig shifted_config;
  shifted_config.grid_offset = 0.1234;
  Completeness shifted(shifted_config);
  shifted.addScan(0.0, wall);
  // 10 m by 2.5 m of wall: 20 x 5 voxels per layer (21 x 6 where the shifted grid cuts the edges).
  EXPECT_EQ(aligned.totalVoxels(), 2u * 20u * 5u);
  EXPECT_LE(shifted.totalVoxels(), 21u * 6u);
  EXPECT_GE(shifted.totalVoxels(), 20u * 5u);
  EXPECT_THROW(Completeness(CompletenessConfig{0.5, 5.0, std::nan("")}), std::invalid_argument);
}

TEST(Completeness, CountsDistinctVoxelsPerWindowAndAveragesCompleteOnes) {
  Completeness cmplt;
  // Window 0 = [100, 105): voxels A, B, C, D (A twice).
  cmplt.addScan(100.0, {in(0, 0, 0), in(1, 0, 0)});
  cmplt.addScan(102.0, {in(0, 0, 0), in(0, 1, 0), in(0, 1, 0)});
  cmplt.addScan(104.9, {in(-3, -3, -3)});
  // Window 1 = [105, 110): A again (counts again: a new window) and E.
  cmplt.addScan(105.0, {in(0, 0, 0)});
  cmplt.addScan(109.0, {in(5, 5, 5)});
  // Window 2 = [110, 115): F, partial.
  cmplt.addScan(110.0, {in(7, 0, 0)});

  const CompletenessReport report = cmplt.report();
  ASSERT_EQ(report.windows.size(), 3u);
  EXPECT_EQ(report.windows[0].voxels, 4u);
  EXPECT_EQ(report.windows[0].scans, 3u);
  EXPECT_DOUBLE_EQ(report.windows[0].start, 100.0);
  EXPECT_DOUBLE_EQ(report.windows[0].end, 105.0);
  EXPECT_EQ(report.windows[1].voxels, 2u);
  EXPECT_EQ(report.windows[1].scans, 2u);
  EXPECT_EQ(report.windows[2].voxels, 1u);
  EXPECT_TRUE(report.windows[0].complete);
  EXPECT_TRUE(report.windows[1].complete);
  EXPECT_FALSE(report.windows[2].complete);
  EXPECT_EQ(report.complete_windows, 2u);
  EXPECT_DOUBLE_EQ(report.mean_voxels_per_window, 3.0);
  EXPECT_EQ(report.total_voxels, 6u);
  EXPECT_EQ(report.scans, 6u);

  // Told that the run lasted to 115 s, the last window counts too.
  const CompletenessReport to_end = cmplt.report(115.0);
  EXPECT_EQ(to_end.complete_windows, 3u);
  EXPECT_DOUBLE_EQ(to_end.mean_voxels_per_window, 7.0 / 3.0);
}

TEST(Completeness, SkipsAndCountsBadInput) {
  Completeness cmplt;
  cmplt.addScan(0.0, {});  // an empty scan is fine
  cmplt.addScan(1.0, {{kFloatNaN, 0, 0}, {0, kInf, 0}, {0, 0, -kInf}, in(1, 1, 1), {1e9f, 0, 0}});
  cmplt.addScan(std::numeric_limits<double>::quiet_NaN(), {in(2, 2, 2)});
  const CompletenessReport report = cmplt.report();
  EXPECT_EQ(report.scans, 2u);
  EXPECT_EQ(report.invalid_scans, 1u);
  EXPECT_EQ(report.invalid_points, 3u);
  EXPECT_EQ(report.out_of_range_points, 1u);
  EXPECT_EQ(report.points, 1u);
  EXPECT_EQ(report.total_voxels, 1u);
}

TEST(Completeness, OutOfOrderStampsGoToTheirWindowWhileItIsHeld) {
  Completeness cmplt;
  cmplt.addScan(0.0, {in(0, 0, 0)});
  cmplt.addScan(6.0, {in(1, 0, 0)});   // window 1
  cmplt.addScan(4.0, {in(2, 0, 0)});   // late, window 0 is still held
  cmplt.addScan(12.0, {in(3, 0, 0)});  // window 2
  cmplt.addScan(3.0, {in(4, 0, 0)});   // window 0 is no longer held: total only
  cmplt.addScan(-1.0, {in(5, 0, 0)});  // before the first stamp: total only
  const CompletenessReport report = cmplt.report();
  ASSERT_EQ(report.windows.size(), 3u);
  EXPECT_EQ(report.windows[0].voxels, 2u);
  EXPECT_EQ(report.windows[1].voxels, 1u);
  EXPECT_EQ(report.windows[2].voxels, 1u);
  EXPECT_EQ(report.late_scans, 2u);
  EXPECT_EQ(report.total_voxels, 6u);
  EXPECT_EQ(report.complete_windows, 2u);
}

TEST(Completeness, GapsAreAbsentWindowsAndShortRunsHaveNoMean) {
  Completeness cmplt;
  cmplt.addScan(0.0, {in(0, 0, 0)});
  cmplt.addScan(4.0, {in(1, 0, 0)});
  CompletenessReport report = cmplt.report();
  EXPECT_EQ(report.complete_windows, 0u);
  EXPECT_TRUE(std::isnan(report.mean_voxels_per_window));

  cmplt.addScan(21.0, {in(0, 0, 0)});  // windows 1..3 had no scan
  report = cmplt.report();
  ASSERT_EQ(report.windows.size(), 2u);
  EXPECT_EQ(report.windows[1].index, 4);
  EXPECT_DOUBLE_EQ(report.mean_voxels_per_window, 2.0);
}

TEST(Completeness, RejectsBadConfiguration) {
  EXPECT_THROW(Completeness({0.0, 5.0}), std::invalid_argument);
  EXPECT_THROW(Completeness({0.5, -1.0}), std::invalid_argument);
}

// Sum of occupied voxels in an OctoMap file read back by OctoMap itself: a pruned leaf at depth d
// stands for 8^(16-d) voxels.
std::size_t occupiedVoxelsIn(const octomap::OcTree& tree) {
  std::size_t voxels = 0;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (tree.isNodeOccupied(*it)) voxels += std::size_t{1} << (3 * (16 - it.getDepth()));
  }
  return voxels;
}

TEST(Completeness, SavesAnOctoMapFileThatReadsBackTheSameVoxels) {
  test::TestDirectory directory;
  Completeness cmplt;
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> uniform(-30.0f, 30.0f);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 5000; ++i) points.emplace_back(uniform(rng), uniform(rng), uniform(rng));
  // A filled 4x4x4-voxel block aligned on the octree: OctoMap prunes it to one leaf.
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) points.push_back(in(x - 8, y, z));
  cmplt.addScan(0.0, points);
  const std::string path = directory.file("voxels.bt");
  EXPECT_EQ(cmplt.saveOctree(path), cmplt.totalVoxels());

  octomap::OcTree tree(0.1);
  ASSERT_TRUE(tree.readBinary(path));
  EXPECT_DOUBLE_EQ(tree.getResolution(), 0.5);
  EXPECT_LT(tree.getNumLeafNodes(), cmplt.totalVoxels());  // pruned
  EXPECT_EQ(occupiedVoxelsIn(tree), cmplt.totalVoxels());
  for (const Eigen::Vector3f& p : points) {
    const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
    ASSERT_NE(node, nullptr);
    EXPECT_TRUE(tree.isNodeOccupied(node));
  }
  EXPECT_EQ(tree.search(100.0, 100.0, 100.0), nullptr);

  const VoxelOctree read = readVoxelOctree(path);
  EXPECT_DOUBLE_EQ(read.resolution, 0.5);
  EXPECT_EQ(read.voxels.size(), cmplt.totalVoxels());
  EXPECT_EQ(asSet(read.voxels), asSet(cmplt.voxels()));
}

TEST(Completeness, SavingToAnImpossiblePathThrowsWithThePath) {
  Completeness cmplt;
  cmplt.addScan(0.0, {in(0, 0, 0)});
  try {
    cmplt.saveOctree("/nonexistent_directory/voxels.bt");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_directory/voxels.bt"), std::string::npos);
  }
}

}  // namespace
}  // namespace uampc::evaluator
