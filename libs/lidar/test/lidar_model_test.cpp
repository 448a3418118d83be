// The LiDAR models' derived figures: the field of view U plans over and the points per frame.
#include "uampc/lidar/lidar_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace uampc::lidar {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(LidarModel, Mid360SeesAllAzimuthsBetweenItsElevationBand) {
  const FieldOfView fov = fieldOfView(livoxMid360());
  EXPECT_DOUBLE_EQ(fov.azimuth_min, -M_PI);
  EXPECT_DOUBLE_EQ(fov.azimuth_max, M_PI);
  EXPECT_NEAR(fov.elevation_min, -7.0 * kDeg, 1e-12);
  EXPECT_NEAR(fov.elevation_max, 52.0 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(nominalPointsPerFrame(livoxMid360()), 20000.0);
}

TEST(LidarModel, SpinningFieldOfViewSpansItsLowestToHighestRing) {
  const FieldOfView fov = fieldOfView(spinningLidar({3.0, -10.0, 7.5}, 30000.0, 5.0, 0.5, 50.0));
  EXPECT_NEAR(fov.elevation_min, -10.0 * kDeg, 1e-12);
  EXPECT_NEAR(fov.elevation_max, 7.5 * kDeg, 1e-12);
  EXPECT_DOUBLE_EQ(nominalPointsPerFrame(spinningLidar({0.0}, 30000.0, 5.0, 0.5, 50.0)), 6000.0);
  const FieldOfView vlp16 = fieldOfView(velodyneVlp16());
  EXPECT_NEAR(vlp16.elevation_min, -15.0 * kDeg, 1e-12);
  EXPECT_NEAR(vlp16.elevation_max, 15.0 * kDeg, 1e-12);
}

TEST(LidarModel, RosetteFieldOfViewIsItsForwardRectangle) {
  const FieldOfView fov = fieldOfView(livoxAvia());
  EXPECT_NEAR(fov.azimuth_min, -35.2 * kDeg, 1e-12);
  EXPECT_NEAR(fov.azimuth_max, 35.2 * kDeg, 1e-12);
  EXPECT_NEAR(fov.elevation_min, -38.6 * kDeg, 1e-12);
  EXPECT_NEAR(fov.elevation_max, 38.6 * kDeg, 1e-12);
}

TEST(LidarModel, UnknownNameIsRejectedWithTheKnownOnes) {
  try {
    lidarModelByName("livox_mid70");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("livox_mid70"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("livox_mid360"), std::string::npos);
  }
}

}  // namespace
}  // namespace uampc::lidar
