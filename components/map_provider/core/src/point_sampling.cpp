#include "uampc/world/point_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "uampc/world/seeded_random.hpp"

namespace uampc::world {

namespace {

// Centroids of the points added, one per voxel of edge voxel_size, in the order voxels are first met.
class VoxelCentroids {
 public:
  explicit VoxelCentroids(double voxel_size) : voxel_size_(voxel_size) {}

  void add(const Eigen::Vector3f& p) {
    auto [it, inserted] = index_.try_emplace(key(p), cells_.size());
    if (inserted) cells_.emplace_back();
    Cell& cell = cells_[it->second];
    cell.sum += p.cast<double>();
    ++cell.count;
  }

  std::vector<Eigen::Vector3f> centroids() const {
    std::vector<Eigen::Vector3f> out;
    out.reserve(cells_.size());
    for (const auto& c : cells_) out.push_back((c.sum / c.count).cast<float>());
    return out;
  }

 private:
  struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
  };

  // 21 bits per axis: unique for +-1e6 voxels each way. A point farther out (a corrupt map's
  // 1e33 m) goes to the outermost voxel of its side: converting its index to an integer unclamped
  // is undefined (on x86 every such point landed in the origin's voxel).
  std::int64_t indexOf(float coordinate) const {
    constexpr double kLimit = 1 << 20;
    return static_cast<std::int64_t>(std::clamp(std::floor(coordinate / voxel_size_), -kLimit, kLimit - 1));
  }
  std::uint64_t key(const Eigen::Vector3f& p) const {
    const std::int64_t ix = indexOf(p.x()), iy = indexOf(p.y()), iz = indexOf(p.z());
    return static_cast<std::uint64_t>((ix & 0x1FFFFF) | ((iy & 0x1FFFFF) << 21) | ((iz & 0x1FFFFF) << 42));
  }

  double voxel_size_;
  std::unordered_map<std::uint64_t, std::size_t> index_;
  std::vector<Cell> cells_;
};

// Calls add(point) for points spread uniformly over the mesh, density_per_m2 on average (see
// sampleSurface).
template <typename Add>
void forEachSurfaceSample(const TriangleMesh& mesh, double density_per_m2, std::uint64_t seed, Add&& add) {
  SeededRandom random(seed);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3f a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const double expected = mesh.triangleArea(i) * density_per_m2;
    const auto n = static_cast<std::int64_t>(std::floor(expected + random.uniform()));
    for (std::int64_t k = 0; k < n; ++k) {
      // Uniform on the triangle: fold the unit square's upper half back onto the lower one.
      double u = random.uniform(), v = random.uniform();
      if (u + v > 1.0) {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      add(Eigen::Vector3f(a + static_cast<float>(u) * (b - a) + static_cast<float>(v) * (c - a)));
    }
  }
}

}  // namespace

std::vector<Eigen::Vector3f> sampleSurface(const TriangleMesh& mesh, double density_per_m2, std::uint64_t seed) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(static_cast<std::size_t>(std::max(0.0, mesh.area() * density_per_m2 * 1.01)));
  forEachSurfaceSample(mesh, density_per_m2, seed, [&](const Eigen::Vector3f& p) { points.push_back(p); });
  return points;
}

std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points, double voxel_size) {
  if (!(voxel_size > 0.0)) return points;
  VoxelCentroids voxels(voxel_size);
  for (const auto& p : points) voxels.add(p);
  return voxels.centroids();
}

std::vector<Eigen::Vector3f> surfacePointMap(const TriangleMesh& mesh, double resolution, std::uint64_t seed) {
  VoxelCentroids voxels(resolution);
  forEachSurfaceSample(mesh, kPointMapSamplesPerVoxelFace / (resolution * resolution), seed,
                       [&](const Eigen::Vector3f& p) { voxels.add(p); });
  return voxels.centroids();
}

double expectedPointMapSize(double area_m2, double resolution) { return area_m2 / (resolution * resolution); }

}  // namespace uampc::world
