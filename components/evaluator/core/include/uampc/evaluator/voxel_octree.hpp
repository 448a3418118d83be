// Voxel sets as OctoMap .bt files (the only place that knows OctoMap).
//
// Voxel index v at resolution r is OctoMap key v + 32768 (OctoMap's key is
// floor(coordinate / r) + 32768), so a voxel maps to exactly one leaf at the finest depth.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace uampc::evaluator {

// Writes voxels as occupied leaves (no ray insertion: the scanned set is what CMPLT counts, free
// space is not). OctoMap prunes eight equal siblings into their parent when writing. Voxels
// outside OctoMap's key range (+-32768) are left out; returns the number written. Throws
// std::runtime_error naming path on failure.
std::size_t writeVoxelOctree(const std::string& path, const std::vector<Eigen::Vector3i>& voxels,
                             double resolution);

// The occupied voxels of a .bt file, expanded to the finest depth, with its resolution.
struct VoxelOctree {
  double resolution = 0.0;
  std::vector<Eigen::Vector3i> voxels;
};
VoxelOctree readVoxelOctree(const std::string& path);

}  // namespace uampc::evaluator
