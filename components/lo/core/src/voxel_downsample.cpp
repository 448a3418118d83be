#include "uampc/lo/voxel_downsample.hpp"

#include <array>
#include <cstdint>
#include <utility>

#include "uampc/lo/voxel.hpp"

namespace uampc::lo {

namespace {

// Morton code of a voxel (10 bits per axis, wrapping: only locality matters).
std::uint32_t mortonCode(const Voxel& v) {
  auto spread = [](std::uint32_t x) {
    x &= 0x3FF;
    x = (x | (x << 16)) & 0x030000FF;
    x = (x | (x << 8)) & 0x0300F00F;
    x = (x | (x << 4)) & 0x030C30C3;
    x = (x | (x << 2)) & 0x09249249;
    return x;
  };
  return spread(static_cast<std::uint32_t>(v.x())) | (spread(static_cast<std::uint32_t>(v.y())) << 1) |
         (spread(static_cast<std::uint32_t>(v.z())) << 2);
}

// Sorts keys code << 32 | index, made in index order, by their Morton code: a stable radix sort
// on the code's 30 bits in three passes of 10 bits, so equal codes keep their index order and the
// result is that of sorting the keys as integers, at a fraction of a comparison sort's cost (which
// was a twentieth of a frame's registration with a budget of 2000 points).
void sortByCode(std::vector<std::uint64_t>& keys) {
  constexpr int kBits = 10;
  constexpr std::uint64_t kDigit = (1u << kBits) - 1;
  std::vector<std::uint64_t> sorted(keys.size());
  for (int shift = 32; shift < 32 + 30; shift += kBits) {
    std::array<std::size_t, kDigit + 1> first{};  // counts, then each digit's first position
    for (const std::uint64_t key : keys) ++first[(key >> shift) & kDigit];
    std::size_t position = 0;
    for (std::size_t& f : first) position += std::exchange(f, position);
    for (const std::uint64_t key : keys) sorted[first[(key >> shift) & kDigit]++] = key;
    keys.swap(sorted);
  }
}

// The indices of the points in Morton order of their voxels (cell_size).
std::vector<std::uint64_t> mortonOrder(const std::vector<TimedPoint>& points, double cell_size) {
  std::vector<std::uint64_t> keyed;
  keyed.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    keyed.push_back(std::uint64_t{mortonCode(voxelOf(points[i].p_B, 1.0 / cell_size))} << 32 | i);
  }
  sortByCode(keyed);
  for (std::uint64_t& key : keyed) key &= 0xFFFFFFFFu;
  return keyed;
}

}  // namespace

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

std::vector<TimedPoint> spatialOrder(const std::vector<TimedPoint>& points, double cell_size) {
  std::vector<TimedPoint> out;
  out.reserve(points.size());
  for (const std::uint64_t index : mortonOrder(points, cell_size)) out.push_back(points[index]);
  return out;
}

std::vector<TimedPoint> spatialSubset(std::vector<TimedPoint> points, std::size_t max_points, double cell_size) {
  if (max_points == 0 || points.size() <= max_points) return points;
  const std::vector<std::uint64_t> order = mortonOrder(points, cell_size);
  std::vector<TimedPoint> out;
  out.reserve(max_points);
  // The middle point of each of max_points equal runs of the ordered points: deterministic, and
  // no run's point is favoured by where the runs start.
  const double run = static_cast<double>(order.size()) / static_cast<double>(max_points);
  for (std::size_t i = 0; i < max_points; ++i) {
    out.push_back(points[order[static_cast<std::size_t>((static_cast<double>(i) + 0.5) * run)]]);
  }
  return out;
}

}  // namespace uampc::lo
