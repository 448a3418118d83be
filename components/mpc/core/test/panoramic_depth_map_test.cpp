#include "uampc/mpc/panoramic_depth_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "synthetic_scenes.hpp"
#include "uampc/mpc/depth_map_normals.hpp"

namespace uampc::mpc {
namespace {

using test::kPi;

Eigen::Isometry3d somePose() {
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  T_WB.translation() = Eigen::Vector3d(3.0, -2.0, 1.5);
  return T_WB;
}

// One pixel per point: the tests that count pixels switch splatting off.
// The pixel arithmetic of these tests is written for 1-degree pixels.
PanoramicDepthMap::Config oneDegree() {
  PanoramicDepthMap::Config config;
  config.width = 360;
  config.height = 180;
  return config;
}

PanoramicDepthMap::Config unsplatted() {
  PanoramicDepthMap::Config config = oneDegree();
  config.point_spacing = 0.0;
  return config;
}

// Direction of the centre of pixel (u, v), by Eq. 5 with our offsets (row 0 = zenith).
Eigen::Vector3d pixelCentreDirection(int u, int v, int width, int height) {
  const double azimuth = -kPi + (u + 0.5) * 2.0 * kPi / width;
  const double elevation = 0.5 * kPi - (v + 0.5) * kPi / height;
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
}

TEST(PanoramicDepthMap, PointAtKnownDirectionLandsInExpectedPixel) {
  PanoramicDepthMap::Config config = unsplatted();
  config.width = 360;
  config.height = 180;
  PanoramicDepthMap map(config);
  const Eigen::Isometry3d T_WB = somePose();
  const int pixels[][2] = {{0, 0}, {359, 179}, {180, 90}, {17, 33}, {271, 150}, {90, 89}};
  for (const auto& uv : pixels) {
    const Eigen::Vector3d p_B = 7.5 * pixelCentreDirection(uv[0], uv[1], 360, 180);
    map.render({Eigen::Vector3d(100, 100, 100), T_WB * p_B}, T_WB);  // first one out of range
    const int pixel = map.pixelIndex(uv[0], uv[1]);
    ASSERT_EQ(map.occupiedCount(), 1U);
    EXPECT_TRUE(map.occupied(pixel)) << "u=" << uv[0] << " v=" << uv[1];
    EXPECT_EQ(map.pointIndex(pixel), 1);
    EXPECT_NEAR(map.range(pixel), 7.5, 1e-5);
    EXPECT_NEAR(map.depthImage()[uv[1] * 360 + uv[0]], 7.5F, 1e-5);
    EXPECT_LT((map.point(pixel).cast<double>() - p_B).norm(), 1e-5);
    EXPECT_EQ(map.pixelOf(p_B), pixel);
  }
}

TEST(PanoramicDepthMap, AxisDirectionsFollowEq5) {
  PanoramicDepthMap map(oneDegree());
  // Azimuth 0 (+x) is the middle column; +y (azimuth +pi/2) is three quarters across.
  EXPECT_EQ(map.pixelOf({1.0, 0.0, 0.01}), map.pixelIndex(180, 89));
  EXPECT_EQ(map.pixelOf({0.0, 1.0, -0.01}), map.pixelIndex(270, 90));
  EXPECT_EQ(map.pixelOf({-1.0, -0.01, 0.0}) % 360, 0);
  EXPECT_EQ(map.pixelOf({0.0, 0.0, 1.0}) / 360, 0);     // zenith: first row
  EXPECT_EQ(map.pixelOf({0.0, 0.0, -1.0}) / 360, 179);  // nadir: last row
}

TEST(PanoramicDepthMap, NearestPointWinsWhateverTheOrder) {
  PanoramicDepthMap map(unsplatted());
  const Eigen::Isometry3d T_WB = somePose();
  const Eigen::Vector3d d = pixelCentreDirection(40, 60, 360, 180);
  const std::vector<Eigen::Vector3d> far_first = {T_WB * (9.0 * d), T_WB * (3.0 * d), T_WB * (6.0 * d)};
  map.render(far_first, T_WB);
  const int pixel = map.pixelIndex(40, 60);
  EXPECT_NEAR(map.range(pixel), 3.0, 1e-5);
  EXPECT_EQ(map.pointIndex(pixel), 1);
  EXPECT_EQ(map.occupiedCount(), 1U);

  const std::vector<Eigen::Vector3d> near_first = {T_WB * (3.0 * d), T_WB * (9.0 * d)};
  map.render(near_first, T_WB);
  EXPECT_NEAR(map.range(pixel), 3.0, 1e-5);
  EXPECT_EQ(map.pointIndex(pixel), 0);
}

TEST(PanoramicDepthMap, EmptyPixelsAreZeroAndRenderReplacesContent) {
  PanoramicDepthMap map(unsplatted());
  map.render({Eigen::Vector3d(5, 0, 0)}, Eigen::Isometry3d::Identity());
  map.render({Eigen::Vector3d(0, 5, 0)}, Eigen::Isometry3d::Identity());
  EXPECT_EQ(map.occupiedCount(), 1U);
  int non_zero = 0;
  for (float d : map.depthImage()) non_zero += d != 0.0F;
  EXPECT_EQ(non_zero, 1);
  EXPECT_EQ(map.depthImage().size(), 360U * 180U);
  EXPECT_FALSE(map.occupied(map.pixelOf({1, 0, 0})));
  EXPECT_EQ(map.pointIndex(map.pixelOf({1, 0, 0})), -1);
}

TEST(PanoramicDepthMap, RangeWindowAndNonFinitePointsAreSkipped) {
  PanoramicDepthMap::Config config = unsplatted();
  config.min_range = 1.0;
  config.max_range = 10.0;
  PanoramicDepthMap map(config);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  map.render(
      {Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(0, 11, 0), Eigen::Vector3d(nan, 0, 1), Eigen::Vector3d(0, 0, 9)},
      Eigen::Isometry3d::Identity());
  EXPECT_EQ(map.occupiedCount(), 1U);
  EXPECT_EQ(map.pointIndex(map.pixelOf({0, 0, 1})), 3);
}

TEST(PanoramicDepthMap, ColumnWrapsMultiTurnAzimuth) {
  PanoramicDepthMap map(oneDegree());
  for (double azimuth : {-3.0, -0.4, 0.0, 1.3, 3.1}) {
    for (int turns : {-3, -1, 1, 7}) {
      EXPECT_EQ(map.column(azimuth + turns * 2.0 * kPi), map.column(azimuth));
    }
  }
}

TEST(PanoramicDepthMap, LookupFillsSmallHolesWithNearestNeighbour) {
  PanoramicDepthMap map(unsplatted());
  const Eigen::Vector3d near_dir = pixelCentreDirection(101, 50, 360, 180);
  const Eigen::Vector3d far_dir = pixelCentreDirection(99, 50, 360, 180);
  map.render({8.0 * far_dir, 4.0 * near_dir}, Eigen::Isometry3d::Identity());
  EXPECT_EQ(map.lookup(100, 50, 0), -1);
  EXPECT_EQ(map.lookup(100, 50, 1), map.pixelIndex(101, 50));
  EXPECT_EQ(map.lookup(99, 50, 1), map.pixelIndex(99, 50));
  EXPECT_EQ(map.lookup(300, 50, 1), -1);
  // Across the seam of the panorama (columns 359 and 0 are neighbours), both ways.
  map.render({5.0 * pixelCentreDirection(359, 60, 360, 180), 5.0 * pixelCentreDirection(1, 70, 360, 180)},
             Eigen::Isometry3d::Identity());
  EXPECT_EQ(map.lookup(0, 60, 1), map.pixelIndex(359, 60));
  EXPECT_EQ(map.lookup(0, 70, 1), map.pixelIndex(1, 70));
  EXPECT_EQ(map.lookup(359, 70, 1), -1);
  EXPECT_EQ(map.lookup(359, 70, 2), map.pixelIndex(1, 70));
}

// The float entry point (the LO's local map as it arrives) renders exactly what the same points
// widened to double render: same pixels, ranges and winners, far from the world origin too.
TEST(PanoramicDepthMap, FloatPointsRenderAsTheirDoubleWidening) {
  const Eigen::Vector3d offset(1234.5, -987.25, 31.0);
  std::vector<Eigen::Vector3f> points_f;
  std::vector<Eigen::Vector3d> points_d;
  for (const Eigen::Vector3d& p : test::corridor(-20.0, 20.0)) {
    points_f.push_back((p + offset).cast<float>());
    points_d.push_back(points_f.back().cast<double>());
  }
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.translation() = offset + Eigen::Vector3d(0.3, -0.2, 0.1);
  T_WB.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  PanoramicDepthMap from_double(oneDegree()), from_float(oneDegree());
  from_double.render(points_d, T_WB);
  from_float.renderFloat(points_f, T_WB);
  ASSERT_GT(from_double.occupiedCount(), 1000u);
  EXPECT_EQ(from_float.occupiedCount(), from_double.occupiedCount());
  EXPECT_EQ(from_float.depthImage(), from_double.depthImage());
  for (int pixel = 0; pixel < from_double.width() * from_double.height(); ++pixel) {
    ASSERT_EQ(from_float.pointIndex(pixel), from_double.pointIndex(pixel)) << pixel;
  }
}

// A near point covers its footprint (0.5 * spacing / range each side), a far one a single pixel;
// nearest still wins inside the footprint.
TEST(PanoramicDepthMap, NearPointsAreSplattedOverTheirFootprint) {
  PanoramicDepthMap::Config config = oneDegree();
  config.point_spacing = 0.3;
  config.max_splat_radius_px = 10;
  PanoramicDepthMap map(config);
  const Eigen::Vector3d d = pixelCentreDirection(100, 90, 360, 180);  // on the horizon
  // At 2 m, 0.15 m each side is 4.3 degrees: pixels 96..104 in both directions.
  map.render({30.0 * d, 2.0 * d, 4.0 * pixelCentreDirection(103, 90, 360, 180)}, Eigen::Isometry3d::Identity());
  for (int du = -4; du <= 4; ++du) {
    for (int dv = -4; dv <= 4; ++dv) {
      EXPECT_EQ(map.pointIndex(map.pixelIndex(100 + du, 90 + dv)), 1) << du << " " << dv;
    }
  }
  EXPECT_FALSE(map.occupied(map.pixelIndex(106, 90)));  // 4 m point: 2 pixels each side
  EXPECT_EQ(map.pointIndex(map.pixelIndex(105, 90)), 2);
  EXPECT_FALSE(map.occupied(map.pixelIndex(100, 95)));
  // The far point lost its only pixel to the near one.
  for (int pixel = 0; pixel < 360 * 180; ++pixel) EXPECT_NE(map.pointIndex(pixel), 0);

  config.max_splat_radius_px = 1;  // the cap holds
  PanoramicDepthMap capped(config);
  capped.render({2.0 * d}, Eigen::Isometry3d::Identity());
  EXPECT_EQ(capped.occupiedCount(), 9U);
}

TEST(PanoramicDepthMap, RejectsInvalidConfig) {
  PanoramicDepthMap::Config config;
  config.width = 0;
  EXPECT_THROW(PanoramicDepthMap{config}, std::invalid_argument);
  config = {};
  config.max_range = config.min_range;
  EXPECT_THROW(PanoramicDepthMap{config}, std::invalid_argument);
}

TEST(DepthMapNormals, PlanesGiveTheirNormalFacingTheOrigin) {
  const test::Cloud cloud = test::corridor(-30.0, 30.0);
  PanoramicDepthMap map(oneDegree());
  map.render(cloud, Eigen::Isometry3d::Identity());
  DepthMapNormals normals;
  normals.reset(map);
  struct Probe {
    Eigen::Vector3d direction;
    Eigen::Vector3d expected;
  };
  const Probe probes[] = {{{0.3, 1.0, 0.2}, {0, -1, 0}},    // left wall
                          {{-0.5, -1.0, -0.1}, {0, 1, 0}},  // right wall
                          {{0.4, 0.2, -1.0}, {0, 0, 1}},    // floor
                          {{-0.6, 0.1, 1.0}, {0, 0, -1}}};  // ceiling
  for (const Probe& probe : probes) {
    const int pixel = map.pixelOf(probe.direction);
    ASSERT_TRUE(map.occupied(pixel));
    const Eigen::Vector3f* n = normals.normal(pixel);
    ASSERT_NE(n, nullptr);
    EXPECT_NEAR(n->norm(), 1.0, 1e-5);
    EXPECT_GT(n->cast<double>().dot(probe.expected), 0.99) << n->transpose();
  }
  // Far down the corridor, where the four surfaces meet, the estimate must not be trusted blindly.
  int accepted = 0;
  int rejected = 0;
  for (int pixel = 0; pixel < map.width() * map.height(); ++pixel) {
    if (!map.occupied(pixel)) continue;
    (normals.normal(pixel) != nullptr ? accepted : rejected)++;
  }
  EXPECT_GT(accepted, 10 * rejected);
  // Cached per point: never more estimates than occupied pixels, and a point splatted over
  // several pixels is estimated once.
  EXPECT_GT(normals.computedCount(), 0);
  EXPECT_LT(normals.computedCount(), static_cast<int>(map.occupiedCount()));
}

// A point splatted over several pixels has one normal, whichever of its pixels asks first: U's
// rays may then resolve pixels in any order. Near walls (large splats) and a corner, where the
// ring around the edge of a splat used to see one face and the ring around the point both.
TEST(DepthMapNormals, APointsNormalDoesNotDependOnWhichOfItsPixelsAsks) {
  test::Cloud cloud = test::corridor(-30.0, 30.0, 1.2);
  test::addRectangle(cloud, {2.0, 0.4, -1.0}, {0, 0.6, 0}, {0, 0, 3}, 0.05);  // a pillar's corner at (2, 0.4)
  test::addRectangle(cloud, {2.0, 0.4, -1.0}, {0.5, 0, 0}, {0, 0, 3}, 0.05);
  PanoramicDepthMap map(oneDegree());
  map.render(cloud, Eigen::Isometry3d::Identity());
  // Every occupied pixel, asked first in raster order and then in reverse order.
  const int pixels = map.width() * map.height();
  DepthMapNormals forward;
  DepthMapNormals backward;
  forward.reset(map);
  backward.reset(map);
  std::vector<const Eigen::Vector3f*> first(pixels, nullptr);
  for (int pixel = 0; pixel < pixels; ++pixel) {
    if (map.occupied(pixel)) first[pixel] = forward.normal(pixel);
  }
  int splatted = 0;
  for (int pixel = pixels - 1; pixel >= 0; --pixel) {
    if (!map.occupied(pixel)) continue;
    splatted += map.centrePixel(pixel) != pixel;
    const Eigen::Vector3f* n = backward.normal(pixel);
    ASSERT_EQ(n == nullptr, first[pixel] == nullptr) << "pixel " << pixel;
    if (n != nullptr) {
      EXPECT_EQ(*n, *first[pixel]) << "pixel " << pixel;
    }
  }
  EXPECT_GT(splatted, 1000);  // the walls 1.2 m away are splatted over many pixels
}

TEST(DepthMapNormals, EmptyPixelHasNoNormal) {
  PanoramicDepthMap map(oneDegree());
  map.render({Eigen::Vector3d(5, 0, 0)}, Eigen::Isometry3d::Identity());
  DepthMapNormals normals;
  normals.reset(map);
  EXPECT_EQ(normals.normal(map.pixelOf({0, 1, 0})), nullptr);
  EXPECT_EQ(normals.normal(map.pixelOf({1, 0, 0})), nullptr);  // single point: no plane
}

// reset() forgets the cached normals by a generation count: a normal asked for after any number
// of resets (past the count's wrap at 65536) is estimated again, on the map as it is now.
TEST(DepthMapNormals, ResetForgetsEveryNormalEvenAfterTheCountWraps) {
  PanoramicDepthMap map(oneDegree());
  map.render(test::corridor(-30.0, 30.0), Eigen::Isometry3d::Identity());
  const int wall = map.pixelOf({0.3, 1.0, 0.2});
  DepthMapNormals normals;
  normals.reset(map);
  ASSERT_NE(normals.normal(wall), nullptr);
  const Eigen::Vector3f first = *normals.normal(wall);
  EXPECT_EQ(normals.computedCount(), 1);  // the second call was answered by the cache
  for (int r = 0; r < 70000; ++r) {
    normals.reset(map);
    if (r == 65533 || r == 65534 || r == 65535 || r == 69999) {  // around the wrap, and after it
      ASSERT_NE(normals.normal(wall), nullptr) << "reset " << r;
      EXPECT_EQ(*normals.normal(wall), first) << "reset " << r;
      EXPECT_EQ(normals.computedCount(), 1) << "reset " << r << ": estimated again once";
    }
  }
  // A new map with a lone point where the wall's point was (so the same cache entry, which is
  // per centre pixel): no plane there, so no normal, and not the wall's stale one.
  const int centre = map.centrePixel(wall);
  const Eigen::Vector3d lone =
      3.0 * pixelCentreDirection(centre % map.width(), centre / map.width(), map.width(), map.height());
  map.render({lone}, Eigen::Isometry3d::Identity());
  ASSERT_EQ(map.centrePixel(centre), centre);
  normals.reset(map);
  EXPECT_EQ(normals.normal(centre), nullptr);
  EXPECT_EQ(normals.computedCount(), 1);
}

}  // namespace
}  // namespace uampc::mpc
