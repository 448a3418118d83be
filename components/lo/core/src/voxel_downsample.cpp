#include "uampc/lo/voxel_downsample.hpp"

#include <cstdint>

#include "uampc/lo/voxel.hpp"

namespace uampc::lo {

std::vector<TimedPoint> voxelDownsample(const std::vector<TimedPoint>& points, double voxel_size) {
  if (voxel_size <= 0.0) return points;
  const double inverse = 1.0 / voxel_size;
  // The voxels seen so far, in an open-addressing set of packed voxel keys (linear probing, at
  // most half full): std::unordered_set allocated a node per voxel and cost more than the rest
  // of the downsampling.
  constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t capacity = 16;
  int shift = 60;  // 64 - log2(capacity), for Fibonacci hashing
  while (capacity < 2 * points.size()) {
    capacity *= 2;
    --shift;
  }
  std::vector<std::uint64_t> seen(capacity, kEmpty);
  const std::size_t mask = capacity - 1;
  std::vector<TimedPoint> out;
  out.reserve(points.size() / 2);
  for (const TimedPoint& point : points) {
    const std::uint64_t key = packVoxel(voxelOf(point.p_B, inverse));
    std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift);
    while (seen[i] != kEmpty && seen[i] != key) i = (i + 1) & mask;
    if (seen[i] == kEmpty) {
      seen[i] = key;
      out.push_back(point);
    }
  }
  return out;
}

}  // namespace uampc::lo
