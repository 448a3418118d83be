// The two builds of the panorama's per-point loops (SSE2 baseline, AVX2) give the same bits, so a
// lockstep run renders the same panoramas on any x86-64 machine.
#include <gtest/gtest.h>

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

TEST(PanoramaKernels, AvxBuildGivesTheBaselineBits) {
  if (!simd::cpuHasAvx2()) GTEST_SKIP() << "this CPU has no AVX2: only the baseline build runs here";
  // n = 1003: not a multiple of any vector width, so the builds' remainder loops run too.
  BaseFrameTransform T;
  T.r_WB = Eigen::Vector3d(1234.5678, -987.25, 3.75);  // far from the origin: the double step counts
  const std::vector<Eigen::Vector3f> points = awkwardPoints(1003, T.r_WB.cast<float>());
  const int n = static_cast<int>(points.size());
  T.R_BW = Eigen::AngleAxisf(0.7F, Eigen::Vector3f(0.2F, -0.3F, 0.9F).normalized()).toRotationMatrix();
  std::vector<float> xb(n), yb(n), zb(n), xa(n), ya(n), za(n);
  builds::toBaseFrameBaseline(points.data(), n, T, xb.data(), yb.data(), zb.data());
  builds::toBaseFrameAvx2(points.data(), n, T, xa.data(), ya.data(), za.data());
  for (int j = 0; j < n; ++j) {
    ASSERT_EQ(bitsOf(xb[j]), bitsOf(xa[j])) << "point " << j;
    ASSERT_EQ(bitsOf(yb[j]), bitsOf(ya[j])) << "point " << j;
    ASSERT_EQ(bitsOf(zb[j]), bitsOf(za[j])) << "point " << j;
    // The single-point form (pixels recompute their point with it) agrees with the blocks.
    const Eigen::Vector3f p = baseFramePoint(points[j], T);
    ASSERT_EQ(bitsOf(p.x()), bitsOf(xb[j])) << "point " << j;
    ASSERT_EQ(bitsOf(p.y()), bitsOf(yb[j])) << "point " << j;
    ASSERT_EQ(bitsOf(p.z()), bitsOf(zb[j])) << "point " << j;
  }

  // Project the awkward points themselves too (as base-frame offsets), not only transformed ones.
  for (int j = 0; j < 200; ++j) xb[j] = points[j].x(), yb[j] = points[j].y(), zb[j] = points[j].z();
  PanoramaProjection c;
  c.min_range2 = 0.25F;
  c.max_range2 = 1600.0F;
  c.width = 360;
  c.height = 180;
  c.columns_per_rad = static_cast<float>(c.width / (2.0 * kPi));
  c.rows_per_rad = static_cast<float>(c.height / kPi);
  std::vector<float> range_b(n), range_a(n);
  std::vector<std::int32_t> column_b(n), column_a(n), row_b(n), row_a(n);
  builds::projectBaseline(n, xb.data(), yb.data(), zb.data(), c, range_b.data(), column_b.data(), row_b.data());
  builds::projectAvx2(n, xb.data(), yb.data(), zb.data(), c, range_a.data(), column_a.data(), row_a.data());
  int inside = 0;
  for (int j = 0; j < n; ++j) {
    ASSERT_EQ(row_b[j], row_a[j]) << "point " << j;
    if (row_b[j] < 0) continue;  // outside the window: column and range are not used
    ++inside;
    ASSERT_EQ(column_b[j], column_a[j]) << "point " << j;
    ASSERT_EQ(bitsOf(range_b[j]), bitsOf(range_a[j])) << "point " << j;
    ASSERT_GE(column_b[j], 0);
    ASSERT_LT(column_b[j], c.width);
    ASSERT_LT(row_b[j], c.height);
  }
  EXPECT_GT(inside, n / 2);  // the comparison covered the common case, not only rejections
}

}  // namespace
}  // namespace uampc::mpc::detail
