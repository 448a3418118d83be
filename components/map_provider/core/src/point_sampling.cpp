#include "uampc/world/point_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "uampc/world/seeded_random.hpp"

namespace uampc::world {

std::vector<Eigen::Vector3f> sampleSurface(const TriangleMesh& mesh, double density_per_m2, std::uint64_t seed) {
  SeededRandom random(seed);
  std::vector<Eigen::Vector3f> points;
  points.reserve(static_cast<std::size_t>(std::max(0.0, mesh.area() * density_per_m2 * 1.01)));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const double expected = mesh.triangleArea(i) * density_per_m2;
    const int n = static_cast<int>(std::floor(expected + random.uniform()));
    for (int k = 0; k < n; ++k) {
      // Uniform on the triangle: fold the unit square's upper half back onto the lower one.
      double u = random.uniform(), v = random.uniform();
      if (u + v > 1.0) {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      points.push_back(a + static_cast<float>(u) * (b - a) + static_cast<float>(v) * (c - a));
    }
  }
  return points;
}

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size) {
  if (!(voxel_size > 0.0)) return points;
  struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
  };
  // 21 bits per axis: unique for +-1e6 voxels each way. A point farther out (a corrupt map's
  // 1e33 m) goes to the outermost voxel of its side: converting its index to an integer unclamped
  // is undefined (on x86 every such point landed in the origin's voxel).
  auto index_of = [&](float coordinate) {
    constexpr double kLimit = 1 << 20;
    return static_cast<std::int64_t>(std::clamp(std::floor(coordinate / voxel_size), -kLimit, kLimit - 1));
  };
  auto key = [&](const Eigen::Vector3f& p) {
    const std::int64_t ix = index_of(p.x()), iy = index_of(p.y()), iz = index_of(p.z());
    return static_cast<std::uint64_t>((ix & 0x1FFFFF) | ((iy & 0x1FFFFF) << 21) | ((iz & 0x1FFFFF) << 42));
  };
  std::unordered_map<std::uint64_t, std::size_t> index;
  std::vector<Cell> cells;
  for (const auto& p : points) {
    auto [it, inserted] = index.try_emplace(key(p), cells.size());
    if (inserted) cells.emplace_back();
    Cell& cell = cells[it->second];
    cell.sum += p.cast<double>();
    ++cell.count;
  }
  std::vector<Eigen::Vector3f> out;
  out.reserve(cells.size());
  for (const auto& c : cells) out.push_back((c.sum / c.count).cast<float>());
  return out;
}

}  // namespace uampc::world
