#include "uampc/lidar/lidar_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace uampc::lidar {

LidarModel livoxMid360() {
  LidarModel m;
  m.name = "livox_mid360";
  m.kind = ScanPatternKind::kZigzag;
  m.points_per_second = 200000.0;
  m.frame_rate_hz = 10.0;
  m.min_range = 1.5;
  m.max_range = 40.0;
  m.range_precision = 0.02;
  m.angular_precision_deg = 0.15;
  m.min_elevation_deg = -7.0;
  m.max_elevation_deg = 52.0;
  m.lasers = 4;
  // About 1 degree between points both ways within a frame (4 lasers, 50k points/s each), and
  // not a multiple of 10 Hz: each frame's sweeps fall 0.73 of a period after the last ones.
  m.sweep_frequency_hz = 437.3;
  return m;
}

LidarModel velodyneVlp16() {
  std::vector<double> elevations;
  for (int k = 0; k < 16; ++k) elevations.push_back(-15.0 + 2.0 * k);
  LidarModel m = spinningLidar(elevations, 288000.0, 10.0, 0.5, 100.0);
  m.name = "velodyne_vlp16";
  m.range_precision = 0.03;
  return m;
}

LidarModel livoxAvia() {
  LidarModel m;
  m.name = "livox_avia";
  m.kind = ScanPatternKind::kRosette;
  m.points_per_second = 240000.0;
  m.frame_rate_hz = 10.0;
  m.min_range = 1.0;
  m.max_range = 200.0;
  m.range_precision = 0.02;
  m.angular_precision_deg = 0.05;
  m.lasers = 6;
  m.horizontal_fov_deg = 70.4;
  m.vertical_fov_deg = 77.2;
  m.prism1_hz = 123.57;
  m.prism2_hz = 89.31;
  return m;
}

namespace {

struct NamedModel {
  const char* name;
  LidarModel (*make)();
};
const NamedModel kNamedModels[] = {
    {"livox_mid360", livoxMid360}, {"velodyne_vlp16", velodyneVlp16}, {"livox_avia", livoxAvia}};

}  // namespace

std::vector<std::string> namedLidarModels() {
  std::vector<std::string> names;
  for (const NamedModel& model : kNamedModels) names.emplace_back(model.name);
  return names;
}

LidarModel lidarModelByName(const std::string& name) {
  for (const NamedModel& model : kNamedModels) {
    if (name == model.name) return model.make();
  }
  std::string expected;
  for (const NamedModel& model : kNamedModels) expected += (expected.empty() ? "" : ", ") + std::string(model.name);
  throw std::invalid_argument("unknown LiDAR model '" + name + "' (expected one of " + expected + ")");
}

LidarModel spinningLidar(std::vector<double> elevations_deg, double points_per_second, double frame_rate_hz,
                         double min_range, double max_range) {
  LidarModel m;
  m.name = "spinning";
  m.kind = ScanPatternKind::kSpinning;
  m.elevations_deg = std::move(elevations_deg);
  m.points_per_second = points_per_second;
  m.frame_rate_hz = frame_rate_hz;
  m.min_range = min_range;
  m.max_range = max_range;
  return m;
}

FieldOfView fieldOfView(const LidarModel& model) {
  constexpr double kDeg = M_PI / 180.0;
  if (model.kind == ScanPatternKind::kRosette) {
    return {-0.5 * model.horizontal_fov_deg * kDeg, 0.5 * model.horizontal_fov_deg * kDeg,
            -0.5 * model.vertical_fov_deg * kDeg, 0.5 * model.vertical_fov_deg * kDeg};
  }
  double lowest = model.min_elevation_deg, highest = model.max_elevation_deg;
  if (model.kind == ScanPatternKind::kSpinning && !model.elevations_deg.empty()) {
    lowest = *std::min_element(model.elevations_deg.begin(), model.elevations_deg.end());
    highest = *std::max_element(model.elevations_deg.begin(), model.elevations_deg.end());
  }
  return {-M_PI, M_PI, lowest * kDeg, highest * kDeg};
}

double nominalPointsPerFrame(const LidarModel& model) { return model.points_per_second / model.frame_rate_hz; }

}  // namespace uampc::lidar
