// A world grown around a given path (e.g. an MCD ground truth): the ground follows the path's
// height, and buildings, trees and walls are scattered around it, never closer than a clearance.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "uampc/world/procedural_worlds.hpp"
#include "uampc/world/seeded_random.hpp"

namespace uampc::world {
namespace {

// The path thinned to samples at least `spacing` apart; keeps the brute-force searches cheap.
std::vector<Eigen::Vector3d> thin(const std::vector<Eigen::Vector3d>& path, double spacing) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : path) {
    if (out.empty() || (p - out.back()).head<2>().norm() >= spacing) out.push_back(p);
  }
  return out;
}

// Ground height below (x, y): the path's height less the base height, blended from the path
// samples by inverse distance to the fourth power (Shepard), so the ground meets the path below
// every sample and has no cliffs between parts of the path at different heights.
double groundHeight(const std::vector<Eigen::Vector3d>& path, double x, double y,
                    double base_height) {
  double weights = 0.0, sum = 0.0;
  for (const auto& p : path) {
    const double d2 = (p.x() - x) * (p.x() - x) + (p.y() - y) * (p.y() - y);
    const double w = 1.0 / (d2 * d2 + 1e-6);
    weights += w;
    sum += w * p.z();
  }
  return sum / weights - base_height;
}

// Horizontal distance from the path to a rectangle of half sizes (hx, hy) at (cx, cy), turned by
// yaw; less than `limit` is enough to reject, so the search stops early.
bool closerThan(const std::vector<Eigen::Vector3d>& path, double cx, double cy, double hx,
                double hy, double yaw, double limit) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (const auto& p : path) {
    const double dx = p.x() - cx, dy = p.y() - cy;
    const double u = std::abs(c * dx + s * dy) - hx;
    const double v = std::abs(-s * dx + c * dy) - hy;
    const double d = std::hypot(std::max(u, 0.0), std::max(v, 0.0));
    if (d < limit) return true;
  }
  return false;
}

struct Footprint {
  double cx, cy, radius;
};

}  // namespace

TriangleMesh makeAroundTrajectory(const std::vector<Eigen::Vector3d>& full_path,
                                  const AroundTrajectoryConfig& config, std::uint64_t seed) {
  if (full_path.empty()) throw std::invalid_argument("makeAroundTrajectory: empty path");
  const std::vector<Eigen::Vector3d> path = thin(full_path, 1.0);
  SeededRandom random(seed);
  TriangleMesh mesh;

  Eigen::Vector2d lo = path.front().head<2>(), hi = lo;
  for (const auto& p : path) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  lo.array() -= config.margin;
  hi.array() += config.margin;

  // Ground: a height field on a regular grid.
  const double cell = config.ground_cell;
  const int nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)) + 1;
  const int ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)) + 1;
  const int first = static_cast<int>(mesh.vertices.size());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = lo.x() + i * cell, y = lo.y() + j * cell;
      mesh.vertices.emplace_back(x, y, groundHeight(path, x, y, config.base_height));
    }
  }
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = first + j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      mesh.triangles.emplace_back(a, b, c);
      mesh.triangles.emplace_back(a, c, d);
    }
  }

  // Objects stand in the band the LiDAR sees along the path (within `band` of it), not scattered
  // over the whole bounding box: a long path's box is mostly far from the path, and a world whose
  // objects are out of range is an open field to the LO wherever the path goes. Densities count
  // per hectare of that band (path length x 2 band).
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).head<2>().norm();
  const double hectares = std::max(1.0, length * 2.0 * config.band / 1e4);
  std::vector<Footprint> taken;
  auto freeOf = [&](double cx, double cy, double radius) {
    return std::none_of(taken.begin(), taken.end(), [&](const Footprint& f) {
      return std::hypot(f.cx - cx, f.cy - cy) < f.radius + radius + 2.0;
    });
  };
  auto place = [&](double hx, double hy, double yaw, double& cx, double& cy) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      // Beside a random point of the path, at least the clearance away (checked below), at most
      // the band (plus the object's own size).
      const Eigen::Vector3d& anchor = path[static_cast<std::size_t>(random.integer(0, static_cast<int>(path.size()) - 1))];
      const double radius = std::hypot(hx, hy);
      const double direction = random.uniform(0.0, 2.0 * M_PI);
      const double distance = config.clearance + radius + random.uniform(0.0, config.band);
      cx = anchor.x() + distance * std::cos(direction);
      cy = anchor.y() + distance * std::sin(direction);
      if (!freeOf(cx, cy, radius)) continue;
      if (closerThan(path, cx, cy, hx, hy, yaw, config.clearance)) continue;
      taken.push_back({cx, cy, radius});
      return true;
    }
    return false;
  };

  const int buildings = static_cast<int>(std::lround(config.buildings_per_hectare * hectares));
  for (int k = 0; k < buildings; ++k) {
    const double hx = random.uniform(4.0, 14.0), hy = random.uniform(4.0, 14.0);
    const double yaw = random.uniform(0.0, M_PI);
    const double height = 3.5 * random.integer(1, 6);
    double cx, cy;
    if (!place(hx, hy, yaw, cx, cy)) continue;
    const double z0 = groundHeight(path, cx, cy, config.base_height) - 1.0;
    mesh.addOrientedBox(Eigen::Vector3f(cx, cy, z0 + 0.5 * (height + 1.0)),
                        Eigen::Vector3f(2 * hx, 2 * hy, height + 1.0), static_cast<float>(yaw));
  }
  const int walls = static_cast<int>(std::lround(config.walls_per_hectare * hectares));
  for (int k = 0; k < walls; ++k) {
    const double hx = random.uniform(5.0, 20.0), hy = 0.15;
    const double yaw = random.uniform(0.0, M_PI);
    const double height = random.uniform(1.0, 3.0);
    double cx, cy;
    if (!place(hx, hy, yaw, cx, cy)) continue;
    const double z0 = groundHeight(path, cx, cy, config.base_height) - 0.5;
    mesh.addOrientedBox(Eigen::Vector3f(cx, cy, z0 + 0.5 * (height + 0.5)),
                        Eigen::Vector3f(2 * hx, 2 * hy, height + 0.5), static_cast<float>(yaw));
  }
  const int trees = static_cast<int>(std::lround(config.trees_per_hectare * hectares));
  for (int k = 0; k < trees; ++k) {
    const double crown = random.uniform(1.2, 2.8);
    double cx, cy;
    if (!place(crown, crown, 0.0, cx, cy)) continue;
    const float z0 = static_cast<float>(groundHeight(path, cx, cy, config.base_height));
    const float trunk = static_cast<float>(random.uniform(1.8, 3.2));
    const float crown_height = static_cast<float>(random.uniform(2.0, 4.5));
    const Eigen::Vector3f base(static_cast<float>(cx), static_cast<float>(cy), z0 - 0.5f);
    mesh.addCylinder(base, 0.2f, trunk + 1.0f, config.segments);
    const Eigen::Vector3f widest =
        base + Eigen::Vector3f(0, 0, 0.5f + trunk + 0.35f * crown_height);
    mesh.addCone(widest, static_cast<float>(crown), -0.35f * crown_height, config.segments);
    mesh.addCone(widest, static_cast<float>(crown), 0.65f * crown_height, config.segments);
  }
  return mesh;
}

}  // namespace uampc::world
