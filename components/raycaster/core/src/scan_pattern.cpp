#include "uampc/raycaster/scan_pattern.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace uampc::raycaster {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

double frac(double x) { return x - std::floor(x); }

Eigen::Vector3f direction(double cos_azimuth, double sin_azimuth, double elevation) {
  const double c = std::cos(elevation);
  return Eigen::Vector3d(c * cos_azimuth, c * sin_azimuth, std::sin(elevation)).cast<float>();
}

Eigen::Vector3f direction(double azimuth, double elevation) {
  return direction(std::cos(azimuth), std::sin(azimuth), elevation);
}

// Phase (in periods, [0, 1)) of a frequency f at time frame_index / frame_rate + t, computed in
// two parts so that late frames keep full precision.
double phase(double f, std::uint64_t frame_index, double frame_rate, double t) {
  return frac(frac(f * static_cast<double>(frame_index) / frame_rate) + f * t);
}

void checkModel(const lidar::LidarModel& m) {
  if (!(m.points_per_second > 0.0) || !(m.frame_rate_hz > 0.0)) {
    throw std::invalid_argument("lidar::LidarModel '" + m.name + "': points_per_second and frame_rate_hz must be positive");
  }
  if (m.kind == lidar::ScanPatternKind::kSpinning && m.elevations_deg.empty()) {
    throw std::invalid_argument("lidar::LidarModel '" + m.name + "': spinning model without rings");
  }
  if (m.kind != lidar::ScanPatternKind::kSpinning && m.lasers < 1) {
    throw std::invalid_argument("lidar::LidarModel '" + m.name + "': needs at least one laser");
  }
}

}  // namespace

std::size_t pointsPerFrame(const lidar::LidarModel& m) {
  checkModel(m);
  const double per_frame = m.points_per_second / m.frame_rate_hz;
  if (m.kind == lidar::ScanPatternKind::kSpinning) {
    const double rings = static_cast<double>(m.elevations_deg.size());
    return static_cast<std::size_t>(std::lround(per_frame / rings)) * m.elevations_deg.size();
  }
  return static_cast<std::size_t>(std::lround(per_frame));
}

std::vector<PatternPoint> scanPattern(const lidar::LidarModel& m, std::uint64_t frame_index) {
  std::vector<PatternPoint> pattern;
  ScanPatternGenerator(m).generate(frame_index, pattern);
  return pattern;
}

ScanPatternGenerator::ScanPatternGenerator(lidar::LidarModel model)
    : model_(std::move(model)), points_(pointsPerFrame(model_)) {
  if (model_.kind == lidar::ScanPatternKind::kSpinning) return;
  times_.resize(points_);
  for (std::size_t k = 0; k < points_; ++k) times_[k] = static_cast<double>(k) / model_.points_per_second;
  for (int laser = 0; laser < model_.lasers; ++laser) {
    laser_phases_.push_back(static_cast<double>(laser) / model_.lasers);
  }
  if (model_.kind != lidar::ScanPatternKind::kZigzag) return;
  cos_azimuth_.resize(points_);
  sin_azimuth_.resize(points_);
  for (std::size_t k = 0; k < points_; ++k) {
    // One head turn per frame.
    const double azimuth = 2.0 * M_PI * times_[k] * model_.frame_rate_hz;
    cos_azimuth_[k] = std::cos(azimuth);
    sin_azimuth_[k] = std::sin(azimuth);
  }
}

void ScanPatternGenerator::generate(std::uint64_t frame_index, std::vector<PatternPoint>& pattern) const {
  const lidar::LidarModel& m = model_;
  const std::size_t n = points_;
  pattern.resize(n);
  const double frame_period = 1.0 / m.frame_rate_hz;
  switch (m.kind) {
    case lidar::ScanPatternKind::kSpinning: {
      const std::size_t rings = m.elevations_deg.size();
      const std::size_t columns = n / rings;
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t column = k / rings, ring = k % rings;
        // Lasers of a column fire one after another, evenly within the column's time slot.
        const double t = (static_cast<double>(column) + static_cast<double>(ring) / static_cast<double>(rings)) /
                         static_cast<double>(columns) * frame_period;
        const double azimuth = 2.0 * M_PI * static_cast<double>(column) / columns;
        pattern[k] = {direction(azimuth, m.elevations_deg[ring] * kDegToRad), static_cast<float>(t),
                      static_cast<std::uint16_t>(ring)};
      }
      break;
    }
    case lidar::ScanPatternKind::kZigzag: {
      const double lo = m.min_elevation_deg * kDegToRad, hi = m.max_elevation_deg * kDegToRad;
      const std::size_t lasers = laser_phases_.size();
      for (std::size_t k = 0, laser = 0; k < n; ++k, laser = laser + 1 == lasers ? 0 : laser + 1) {
        const double t = times_[k];
        // The lasers sweep the elevation band as triangle waves.
        const double p = frac(phase(m.sweep_frequency_hz, frame_index, m.frame_rate_hz, t) + laser_phases_[laser]);
        const double wave = p < 0.5 ? 2.0 * p : 2.0 - 2.0 * p;
        pattern[k] = {direction(cos_azimuth_[k], sin_azimuth_[k], lo + (hi - lo) * wave), static_cast<float>(t),
                      static_cast<std::uint16_t>(laser)};
      }
      break;
    }
    case lidar::ScanPatternKind::kRosette: {
      const double half_h = 0.5 * m.horizontal_fov_deg * kDegToRad;
      const double half_v = 0.5 * m.vertical_fov_deg * kDegToRad;
      const std::size_t lasers = laser_phases_.size();
      for (std::size_t k = 0, laser = 0; k < n; ++k, laser = laser + 1 == lasers ? 0 : laser + 1) {
        const double t = times_[k];
        // Two prisms turning opposite ways; their deflections add up to a point in the unit disk.
        const double a1 = 2.0 * M_PI * (phase(m.prism1_hz, frame_index, m.frame_rate_hz, t) + laser_phases_[laser]);
        const double a2 = -2.0 * M_PI * phase(m.prism2_hz, frame_index, m.frame_rate_hz, t);
        const double u = 0.5 * (std::cos(a1) + std::cos(a2));
        const double v = 0.5 * (std::sin(a1) + std::sin(a2));
        pattern[k] = {direction(u * half_h, v * half_v), static_cast<float>(t), static_cast<std::uint16_t>(laser)};
      }
      break;
    }
  }
}

}  // namespace uampc::raycaster
