// Point clouds from surfaces and point clouds made lighter.
#pragma once

#include <cstdint>
#include <vector>

#include "uampc/world/triangle_mesh.hpp"

namespace uampc::world {

// Points spread uniformly over the mesh surfaces, density_per_m2 on average. Each triangle gets
// floor(area * density + u) points, u uniform in [0, 1), at uniform barycentric positions; the
// same mesh, density and seed give the same points on every machine.
std::vector<Eigen::Vector3f> sampleSurface(const TriangleMesh& mesh, double density_per_m2,
                                           std::uint64_t seed);

// One point per occupied voxel of edge voxel_size (m): the centroid of the points in it, in the
// order in which voxels are first met. voxel_size <= 0 returns the points unchanged.
std::vector<Eigen::Vector3f> voxelDownsample(const std::vector<Eigen::Vector3f>& points,
                                             double voxel_size);

}  // namespace uampc::world
