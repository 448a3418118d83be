// A world grown around a given path (e.g. an MCD ground truth): the ground follows the path's
// height, and buildings, trees and walls are scattered around it, never closer than a clearance.
// A density profile (density_profile.hpp) leaves stretches of the path open: their objects are not
// built, and a lawn, a car park, one long wall or a street of two long walls stands there instead.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "uampc/world/density_profile.hpp"
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
double groundHeight(const std::vector<Eigen::Vector3d>& path, double x, double y, double base_height) {
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
bool closerThan(const std::vector<Eigen::Vector3d>& path, double cx, double cy, double hx, double hy, double yaw,
                double limit) {
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

// No footprint within 2 m of a circle of this radius at (cx, cy).
bool freeOf(const std::vector<Footprint>& taken, double cx, double cy, double radius) {
  return std::none_of(taken.begin(), taken.end(),
                      [&](const Footprint& f) { return std::hypot(f.cx - cx, f.cy - cy) < f.radius + radius + 2.0; });
}

// The thinned path cut into its density profile's stretches: which stretch every sample, and so
// every place (see stretchAt), belongs to.
class StretchedPath {
 public:
  StretchedPath(const std::vector<Eigen::Vector3d>& samples, const DensityProfileConfig& profile, std::uint64_t seed)
      : samples_(samples) {
    arc_.push_back(0.0);
    for (std::size_t i = 1; i < samples.size(); ++i)
      arc_.push_back(arc_.back() + (samples[i] - samples[i - 1]).head<2>().norm());
    stretches_ = drawStretches(arc_.back(), profile, seed);
    std::size_t k = 0;
    for (double s : arc_) {
      while (k + 1 < stretches_.size() && s >= stretches_[k].end) ++k;
      stretch_of_.push_back(k);
    }
  }

  const std::vector<PathStretch>& stretches() const { return stretches_; }
  const std::vector<Eigen::Vector3d>& samples() const { return samples_; }
  double arc(std::size_t i) const { return arc_[i]; }

  // The stretch a place belongs to: that of the nearest sample of the first pass of the path
  // within `reach` of it (the nearest sample of all if none is). Where the path passes a place
  // once this is simply its nearest sample's stretch; where it comes back, the first visit
  // decides, so the start of a run looks as its first stretches say whatever comes later.
  std::size_t stretchAt(double x, double y, double reach) const {
    const Eigen::Vector2d place(x, y);
    std::size_t best = 0;
    double best_d2 = 1e300;
    bool in_pass = false;
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const double d2 = (samples_[i].head<2>() - place).squaredNorm();
      const bool within = d2 < reach * reach;
      if (in_pass && !within) break;  // the first pass has gone by
      if (within && !in_pass) best_d2 = 1e300;
      in_pass |= within;
      if (d2 < best_d2) {
        best_d2 = d2;
        best = i;
      }
    }
    return stretch_of_[best];
  }

  // First and one-past-last sample of stretch k (empty when no sample falls in it).
  std::pair<std::size_t, std::size_t> samplesOf(std::size_t k) const {
    const auto first = std::lower_bound(stretch_of_.begin(), stretch_of_.end(), k);
    const auto last = std::upper_bound(first, stretch_of_.end(), k);
    return {static_cast<std::size_t>(first - stretch_of_.begin()),
            static_cast<std::size_t>(last - stretch_of_.begin())};
  }

 private:
  const std::vector<Eigen::Vector3d>& samples_;
  std::vector<double> arc_;
  std::vector<PathStretch> stretches_;
  std::vector<std::size_t> stretch_of_;
};

// Horizontal unit vector along the path at sample i (from its neighbours).
Eigen::Vector2d directionAt(const std::vector<Eigen::Vector3d>& path, std::size_t i) {
  const std::size_t a = i > 0 ? i - 1 : i, b = std::min(i + 1, path.size() - 1);
  const Eigen::Vector2d d = (path[b] - path[a]).head<2>();
  return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::UnitX();
}

// A long plain wall beside stretch k, `distance` from the path on `side` (+1 left, -1 right),
// following it in straight pieces of config.wall_segment; pieces that would come within the
// clearance of the path (where it bends or comes back) or belong to another stretch are left out.
void addLongWall(TriangleMesh& mesh, const StretchedPath& path, std::size_t k, double side, double distance,
                 double height, const AroundTrajectoryConfig& config) {
  const auto& p = path.samples();
  const auto [first, end] = path.samplesOf(k);
  if (end <= first + 1) return;
  const double half_thickness = 0.15;
  for (std::size_t a = first, b; a + 1 < end; a = b) {
    for (b = a + 1; b + 1 < end && path.arc(b) - path.arc(a) < config.wall_segment;) ++b;
    const Eigen::Vector2d chord = (p[b] - p[a]).head<2>();
    if (chord.norm() < 1e-3) continue;
    const Eigen::Vector2d along = chord.normalized(), left(-along.y(), along.x());
    const Eigen::Vector2d centre = 0.5 * (p[a] + p[b]).head<2>() + side * (distance + half_thickness) * left;
    const double hx = 0.5 * chord.norm() + 0.5;  // overlapping a little, no gaps at bends
    const double yaw = std::atan2(along.y(), along.x());
    if (closerThan(p, centre.x(), centre.y(), hx, half_thickness, yaw, config.clearance)) continue;
    if (path.stretchAt(centre.x(), centre.y(), config.clearance + config.band) != k) continue;
    const double z0 = groundHeight(p, centre.x(), centre.y(), config.base_height) - 0.5;
    mesh.addOrientedBox(Eigen::Vector3f(centre.x(), centre.y(), z0 + 0.5 * (height + 0.5)),
                        Eigen::Vector3f(2 * hx, 2 * half_thickness, height + 0.5), static_cast<float>(yaw));
  }
}

// A few parked cars (low boxes) beside stretch k, along or across the path, kept apart from each
// other and from the objects already placed.
void addCarPark(TriangleMesh& mesh, const StretchedPath& path, std::size_t k, const AroundTrajectoryConfig& config,
                SeededRandom& random, std::vector<Footprint>& taken) {
  const auto& p = path.samples();
  const auto [first, end] = path.samplesOf(k);
  if (end <= first) return;
  const double length = 4.5, width = 1.8, height = 1.5, radius = std::hypot(length, width) / 2;
  const long cars = std::max(1L, std::lround(path.stretches()[k].length() / config.car_spacing));
  for (long c = 0; c < cars; ++c) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const std::size_t i =
          static_cast<std::size_t>(random.integer(static_cast<int>(first), static_cast<int>(end) - 1));
      const Eigen::Vector2d along = directionAt(p, i), left(-along.y(), along.x());
      const double side = random.chance(0.5) ? 1.0 : -1.0;
      const double yaw = std::atan2(along.y(), along.x()) + (random.chance(0.5) ? M_PI / 2 : 0.0);
      const double distance = config.clearance + radius + random.uniform(0.0, config.car_reach);
      const Eigen::Vector2d centre = p[i].head<2>() + side * distance * left;
      if (!freeOf(taken, centre.x(), centre.y(), radius)) continue;
      if (closerThan(p, centre.x(), centre.y(), length / 2, width / 2, yaw, config.clearance)) continue;
      if (path.stretchAt(centre.x(), centre.y(), config.clearance + config.band) != k) continue;
      taken.push_back({centre.x(), centre.y(), radius});
      const double z0 = groundHeight(p, centre.x(), centre.y(), config.base_height) - 0.5;
      mesh.addOrientedBox(Eigen::Vector3f(centre.x(), centre.y(), z0 + 0.5 * (height + 0.5)),
                          Eigen::Vector3f(length, width, height + 0.5), static_cast<float>(yaw));
      break;
    }
  }
}

// What stands along the open stretches, drawn from a stream of its own.
void addOpenStretches(TriangleMesh& mesh, const StretchedPath& path, const AroundTrajectoryConfig& config,
                      std::uint64_t seed, std::vector<Footprint>& taken) {
  SeededRandom random(mixSeed(seed, 0x4675726e69747572ull));  // "Furnitur"
  for (std::size_t k = 0; k < path.stretches().size(); ++k) {
    switch (path.stretches()[k].kind) {
      case StretchKind::kBuiltUp:
      case StretchKind::kLawn:
        break;
      case StretchKind::kCarPark:
        addCarPark(mesh, path, k, config, random, taken);
        break;
      case StretchKind::kOneWall: {
        // A garden or boundary wall, or a windowless facade.
        const double side = random.chance(0.5) ? 1.0 : -1.0;
        const double distance = config.clearance + random.uniform(1.0, 8.0);
        addLongWall(mesh, path, k, side, distance, random.uniform(2.0, 5.0), config);
        break;
      }
      case StretchKind::kStreet:
        // Plain facades on both sides: the corridor of the outdoors.
        for (const double side : {1.0, -1.0}) {
          const double distance = config.clearance + random.uniform(1.0, 5.0);
          addLongWall(mesh, path, k, side, distance, random.uniform(6.0, 15.0), config);
        }
        break;
    }
  }
}

}  // namespace

TriangleMesh makeAroundTrajectory(const std::vector<Eigen::Vector3d>& full_path, const AroundTrajectoryConfig& config,
                                  std::uint64_t seed) {
  if (full_path.empty()) throw std::invalid_argument("makeAroundTrajectory: empty path");
  checkDensityProfile(config.density);
  const std::vector<Eigen::Vector3d> path = thin(full_path, 1.0);
  const StretchedPath stretched(path, config.density, seed);
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
  auto place = [&](double hx, double hy, double yaw, double& cx, double& cy) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      // Beside a random point of the path, at least the clearance away (checked below), at most
      // the band (plus the object's own size).
      const Eigen::Vector3d& anchor =
          path[static_cast<std::size_t>(random.integer(0, static_cast<int>(path.size()) - 1))];
      const double radius = std::hypot(hx, hy);
      const double direction = random.uniform(0.0, 2.0 * M_PI);
      const double distance = config.clearance + radius + random.uniform(0.0, config.band);
      cx = anchor.x() + distance * std::cos(direction);
      cy = anchor.y() + distance * std::sin(direction);
      if (!freeOf(taken, cx, cy, radius)) continue;
      if (closerThan(path, cx, cy, hx, hy, yaw, config.clearance)) continue;
      // An object of an open stretch is not built (and gives its place back). In a rich world
      // no stretch is open, and the objects are those of the world before profiles existed.
      if (stretched.stretches()[stretched.stretchAt(cx, cy, config.clearance + config.band)].open()) return false;
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
    const Eigen::Vector3f widest = base + Eigen::Vector3f(0, 0, 0.5f + trunk + 0.35f * crown_height);
    mesh.addCone(widest, static_cast<float>(crown), -0.35f * crown_height, config.segments);
    mesh.addCone(widest, static_cast<float>(crown), 0.65f * crown_height, config.segments);
  }
  addOpenStretches(mesh, stretched, config, seed, taken);
  return mesh;
}

}  // namespace uampc::world
