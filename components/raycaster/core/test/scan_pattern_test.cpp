#include "uampc/raycaster/scan_pattern.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace uampc::raycaster {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

double elevationDeg(const Eigen::Vector3f& d) { return std::asin(d.z()) * kRadToDeg; }
double azimuthDeg(const Eigen::Vector3f& d) { return std::atan2(d.y(), d.x()) * kRadToDeg; }

// Number of distinct cells (cell_deg x cell_deg in azimuth and elevation) hit by the frames.
std::size_t coveredCells(const lidar::LidarModel& model, int frames, double cell_deg) {
  std::set<std::pair<int, int>> cells;
  for (int f = 0; f < frames; ++f) {
    for (const auto& p : scanPattern(model, static_cast<std::uint64_t>(f))) {
      cells.emplace(static_cast<int>(std::floor(azimuthDeg(p.direction) / cell_deg)),
                    static_cast<int>(std::floor(elevationDeg(p.direction) / cell_deg)));
    }
  }
  return cells.size();
}

void expectWellFormed(const lidar::LidarModel& model, const std::vector<PatternPoint>& pattern) {
  ASSERT_EQ(pattern.size(), pointsPerFrame(model));
  float last = -1.0f;
  for (const auto& p : pattern) {
    ASSERT_NEAR(p.direction.norm(), 1.0f, 1e-5f);
    ASSERT_GE(p.time_offset, last);
    last = p.time_offset;
  }
  EXPECT_GE(pattern.front().time_offset, 0.0f);
  EXPECT_LT(pattern.back().time_offset, 1.0 / model.frame_rate_hz);
  EXPECT_GT(pattern.back().time_offset, 0.99 / model.frame_rate_hz);
}

TEST(ScanPattern, Mid360MatchesTheModel) {
  const lidar::LidarModel model = lidar::livoxMid360();
  const auto pattern = scanPattern(model, 0);
  expectWellFormed(model, pattern);
  EXPECT_EQ(pattern.size(), 20000u);  // 200k points/s at 10 Hz
  double lo = 90, hi = -90;
  std::set<int> azimuth_bins, rings;
  for (const auto& p : pattern) {
    lo = std::min(lo, elevationDeg(p.direction));
    hi = std::max(hi, elevationDeg(p.direction));
    azimuth_bins.insert(static_cast<int>(std::floor((azimuthDeg(p.direction) + 180.0) / 10.0)) %
                        36);
    rings.insert(p.ring);
  }
  EXPECT_GE(lo, -7.0 - 1e-4);
  EXPECT_LE(hi, 52.0 + 1e-4);
  EXPECT_LT(lo, -6.0);
  EXPECT_GT(hi, 51.0);
  EXPECT_EQ(azimuth_bins.size(), 36u);  // all around
  EXPECT_EQ(rings.size(), 4u);
}

TEST(ScanPattern, Mid360IsNonRepetitiveAndCoverageBuildsUp) {
  const lidar::LidarModel model = lidar::livoxMid360();
  const auto a = scanPattern(model, 0), b = scanPattern(model, 1);
  EXPECT_GT((a[100].direction - b[100].direction).norm(), 1e-3f);
  EXPECT_EQ(scanPattern(model, 1)[5].direction, b[5].direction);  // deterministic
  const std::size_t one = coveredCells(model, 1, 0.5);
  const std::size_t ten = coveredCells(model, 10, 0.5);
  // 360 x 59 degrees in 0.5 degree cells: 84960 cells.
  EXPECT_GT(ten, 2 * one);
  EXPECT_GT(ten, 84960u * 6 / 10);
}

TEST(ScanPattern, Vlp16RingsAndRepetition) {
  const lidar::LidarModel model = lidar::velodyneVlp16();
  const auto pattern = scanPattern(model, 0);
  expectWellFormed(model, pattern);
  EXPECT_EQ(pattern.size(), 28800u);  // 1800 columns of 0.2 degrees, 16 rings
  for (const auto& p : pattern) {
    ASSERT_LT(p.ring, 16);
    ASSERT_NEAR(elevationDeg(p.direction), -15.0 + 2.0 * p.ring, 1e-3);
  }
  EXPECT_EQ(scanPattern(model, 7)[1234].direction, pattern[1234].direction);
}

TEST(ScanPattern, AviaRosetteStaysInItsFieldOfView) {
  const lidar::LidarModel model = lidar::livoxAvia();
  const auto pattern = scanPattern(model, 0);
  expectWellFormed(model, pattern);
  double max_az = 0, max_el = 0;
  for (const auto& p : pattern) {
    ASSERT_GT(p.direction.x(), 0.0f);
    max_az = std::max(max_az, std::abs(azimuthDeg(p.direction)));
    max_el = std::max(max_el, std::abs(elevationDeg(p.direction)));
  }
  EXPECT_LE(max_az, 35.2 + 1e-3);
  EXPECT_LE(max_el, 38.6 + 1e-3);
  EXPECT_GT(max_az, 30.0);
  EXPECT_GT(max_el, 33.0);
  // The ellipse of view holds about 107k cells of 0.2 degrees; one frame has 24k points.
  const std::size_t one = coveredCells(model, 1, 0.2), ten = coveredCells(model, 10, 0.2);
  EXPECT_GT(ten, 2 * one);
  EXPECT_GT(ten, 107000u * 6 / 10);
}

TEST(ScanPattern, GenericSpinningFromATable) {
  const lidar::LidarModel model = lidar::spinningLidar({-10.0, 0.0, 10.0}, 30000.0, 10.0, 0.3, 50.0);
  const auto pattern = scanPattern(model, 3);
  expectWellFormed(model, pattern);
  EXPECT_EQ(pattern.size(), 3000u);
  EXPECT_NEAR(elevationDeg(pattern[2].direction), 10.0, 1e-4);
  EXPECT_THROW(scanPattern(lidar::spinningLidar({}, 1000.0, 10.0, 0.3, 5.0), 0), std::invalid_argument);
  EXPECT_EQ(lidar::lidarModelByName("velodyne_vlp16").elevations_deg.size(), 16u);
  EXPECT_THROW(lidar::lidarModelByName("ouster"), std::invalid_argument);
}

}  // namespace
}  // namespace uampc::raycaster
