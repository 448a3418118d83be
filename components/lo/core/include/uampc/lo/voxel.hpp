// Integer voxel coordinates and their hash, shared by downsampling and the local map.
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

struct VoxelHash {
  std::size_t operator()(const Voxel& v) const {
    const auto x = static_cast<std::uint64_t>(static_cast<std::uint32_t>(v.x()));
    const auto y = static_cast<std::uint64_t>(static_cast<std::uint32_t>(v.y()));
    const auto z = static_cast<std::uint64_t>(static_cast<std::uint32_t>(v.z()));
    return static_cast<std::size_t>((x * 73856093u) ^ (y * 19349669u) ^ (z * 83492791u));
  }
};

}  // namespace uampc::lo
