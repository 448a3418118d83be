// The two builds of the panorama's per-point loops (SSE2 baseline, AVX2) give the same bits, so a
// lockstep run renders the same panoramas on any x86-64 machine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "../src/angles.hpp"
#include "../src/panorama_kernels.hpp"
#include "uampc/simd/dispatch.hpp"

namespace uampc::mpc::detail {
namespace {

// Points around a base pose, with the values that take a loop's other branches: NaN, infinities,
// zeros of both signs, points on the axes (atan2's octant boundaries), and far and near ones.
// The ordinary points lie within 30 m of centre along each axis.
std::vector<Eigen::Vector3f> awkwardPoints(std::size_t count, const Eigen::Vector3f& centre) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-30.0F, 30.0F);
  std::vector<Eigen::Vector3f> points;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float specials[] = {0.0F, -0.0F, 1.0F, -1.0F, nan, inf, -inf, 1e-30F, 3.0e38F, 100.5F};
  for (float a : specials) {
    for (float b : specials) points.emplace_back(a, b, 1.5F), points.emplace_back(1.0F, a, b);
  }
  while (points.size() < count) {
    points.push_back(centre + Eigen::Vector3f(coordinate(rng), coordinate(rng), 0.1F * coordinate(rng)));
  }
  return points;
}

std::uint32_t bitsOf(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

PanoramaProjection oneDegree() {
  PanoramaProjection c;
  c.min_range2 = 0.25F;
  c.max_range2 = 1600.0F;
  c.width = 360;
  c.height = 180;
  c.columns_per_rad = static_cast<float>(c.width / (2.0 * kPi));
  c.rows_per_rad = static_cast<float>(c.height / kPi);
  return c;
}

// Bins the points block by block with both builds and compares every output bit for bit; checks
// that baseFramePoint gives the base-frame point each range was computed from. Returns how many
// points fell in the range window (so that the comparison is known to cover the common case).
int compareBuilds(const std::vector<Eigen::Vector3f>& points, const BaseFrameTransform& T) {
  const PanoramaProjection c = oneDegree();
  int inside = 0;
  for (std::size_t begin = 0; begin < points.size(); begin += kBinBlock) {
    // The last block is short: the builds' remainder loops run too.
    const int n = static_cast<int>(std::min<std::size_t>(kBinBlock, points.size() - begin));
    float range_b[kBinBlock], range_a[kBinBlock];
    std::int32_t column_b[kBinBlock], column_a[kBinBlock], row_b[kBinBlock], row_a[kBinBlock];
    builds::binPointsBaseline(&points[begin], n, T, c, range_b, column_b, row_b);
    builds::binPointsAvx2(&points[begin], n, T, c, range_a, column_a, row_a);
    for (int j = 0; j < n; ++j) {
      const std::size_t i = begin + static_cast<std::size_t>(j);
      EXPECT_EQ(row_b[j], row_a[j]) << "point " << i;
      if (row_b[j] < 0) continue;  // outside the window: column and range are not used
      ++inside;
      EXPECT_EQ(column_b[j], column_a[j]) << "point " << i;
      EXPECT_EQ(bitsOf(range_b[j]), bitsOf(range_a[j])) << "point " << i;
      EXPECT_GE(column_b[j], 0);
      EXPECT_LT(column_b[j], c.width);
      EXPECT_LT(row_b[j], c.height);
      // The panorama stores this point for the pixel: the range must come from the same bits.
      const Eigen::Vector3f p = baseFramePoint(points[i], T);
      EXPECT_EQ(bitsOf(std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z())), bitsOf(range_b[j])) << "point " << i;
    }
  }
  return inside;
}

TEST(PanoramaKernels, AvxBuildGivesTheBaselineBits) {
  if (!simd::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: only the baseline build runs here";
  BaseFrameTransform far;
  far.r_WB = Eigen::Vector3d(1234.5678, -987.25, 3.75);  // far from the origin: the double step counts
  far.R_BW = Eigen::AngleAxisf(0.7F, Eigen::Vector3f(0.2F, -0.3F, 0.9F).normalized()).toRotationMatrix();
  const std::vector<Eigen::Vector3f> points = awkwardPoints(1003, far.r_WB.cast<float>());
  EXPECT_GT(compareBuilds(points, far), static_cast<int>(points.size()) / 2);
  // At the origin, unrotated: the awkward values reach the binning as they are (NaN, zeros, axes).
  const BaseFrameTransform origin{Eigen::Vector3d::Zero(), Eigen::Matrix3f::Identity()};
  EXPECT_GT(compareBuilds(awkwardPoints(1003, Eigen::Vector3f::Zero()), origin), 500);
}

}  // namespace
}  // namespace uampc::mpc::detail
