#include "uampc/world/generated_paths.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace uampc::world {
namespace {

// Each corner's legs are cut back by up to `cut` and the corner replaced by a quadratic Bezier arc
// (tangent to both legs), so the path turns smoothly but stays close to its waypoints.
std::vector<Eigen::Vector3d> roundCorners(const std::vector<Eigen::Vector3d>& p, bool closed,
                                          double cut) {
  std::vector<Eigen::Vector3d> out;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!closed && (i == 0 || i + 1 == n)) {
      out.push_back(p[i]);
      continue;
    }
    const Eigen::Vector3d& prev = p[(i + n - 1) % n];
    const Eigen::Vector3d& corner = p[i];
    const Eigen::Vector3d& next = p[(i + 1) % n];
    const double la = (corner - prev).norm(), lb = (next - corner).norm();
    const double d = std::min({cut, 0.5 * la, 0.5 * lb});
    if (!(d > 1e-9)) {
      out.push_back(corner);
      continue;
    }
    const Eigen::Vector3d a = corner - (corner - prev) / la * d;
    const Eigen::Vector3d b = corner + (next - corner) / lb * d;
    constexpr int kSteps = 8;
    for (int k = 0; k <= kSteps; ++k) {
      const double s = static_cast<double>(k) / kSteps;
      out.push_back((1 - s) * (1 - s) * a + 2 * s * (1 - s) * corner + s * s * b);
    }
  }
  return out;
}

// A polyline parametrised by arc length.
struct Polyline {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> s;  // cumulative length at each point
  double length() const { return s.back(); }
  Eigen::Vector3d at(double t) const {
    t = std::clamp(t, 0.0, length());
    auto it = std::upper_bound(s.begin(), s.end(), t);
    if (it == s.end()) return points.back();
    const std::size_t i = static_cast<std::size_t>(it - s.begin());
    const double seg = s[i] - s[i - 1];
    const double u = seg > 0.0 ? (t - s[i - 1]) / seg : 0.0;
    return (1.0 - u) * points[i - 1] + u * points[i];
  }
};

}  // namespace

Trajectory pathThroughWaypoints(const std::vector<Eigen::Vector3d>& waypoints,
                                const GeneratedPathConfig& config) {
  if (waypoints.size() < 2) throw std::invalid_argument("pathThroughWaypoints: need 2 waypoints");
  if (!(config.speed > 0.0) || !(config.rate_hz > 0.0)) {
    throw std::invalid_argument("pathThroughWaypoints: speed and rate_hz must be positive");
  }
  std::vector<Eigen::Vector3d> p = waypoints;
  if (config.corner_cut > 0.0) p = roundCorners(p, config.closed, config.corner_cut);
  if (config.closed) p.push_back(p.front());

  Polyline line;
  line.points = p;
  line.s.assign(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) line.s[i] = line.s[i - 1] + (p[i] - p[i - 1]).norm();
  if (!(line.length() > 0.0)) throw std::invalid_argument("pathThroughWaypoints: zero length");

  const double L = line.length();
  const double total = config.closed ? L * std::max(1, config.laps) : L;
  const double step = config.speed / config.rate_hz;
  const int samples = static_cast<int>(std::floor(total / step + 1e-9)) + 1;
  auto position = [&](double s) {
    if (config.closed) s = std::fmod(std::fmod(s, L) + L, L);
    return line.at(s);
  };

  std::vector<TimedPose> poses;
  poses.reserve(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k) {
    const double s = k * step;
    TimedPose pose;
    pose.time = config.start_time + k / config.rate_hz;
    pose.position = position(s);
    // Heading from a central difference over +-1 m (one-sided at the ends of an open path).
    const double ahead = config.closed ? s + 1.0 : std::min(s + 1.0, L);
    const double behind = config.closed ? s - 1.0 : std::max(s - 1.0, 0.0);
    const Eigen::Vector3d d = position(ahead) - position(behind);
    const double yaw = std::atan2(d.y(), d.x());
    pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    poses.push_back(pose);
  }
  return Trajectory(std::move(poses));
}

}  // namespace uampc::world
