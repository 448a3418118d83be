// Integer voxel coordinates and their packing into one integer, shared by downsampling and the local map.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace uampc::lo {

using Voxel = Eigen::Vector3i;

inline Voxel voxelOf(const Eigen::Vector3d& p, double inverse_voxel_size) {
  return Voxel(static_cast<int>(std::floor(p.x() * inverse_voxel_size)),
               static_cast<int>(std::floor(p.y() * inverse_voxel_size)),
               static_cast<int>(std::floor(p.z() * inverse_voxel_size)));
}

// A voxel as one integer, 21 bits per axis: distinct for |coordinates| below 2^20 voxels (300 km
// at 0.3 m), far beyond a scan's range. Never equal to ~0, which tables use for "empty".
inline std::uint64_t packVoxel(const Voxel& v) {
  constexpr std::uint64_t kBias = std::uint64_t{1} << 20;
  constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
  return ((static_cast<std::uint64_t>(v.x()) + kBias) & kMask) |
         (((static_cast<std::uint64_t>(v.y()) + kBias) & kMask) << 21) |
         (((static_cast<std::uint64_t>(v.z()) + kBias) & kMask) << 42);
}

}  // namespace uampc::lo
