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

// The mesh as a point map of the given resolution (m), as a dataset's map downsampled to it: points
// spread over the surfaces (kPointMapSamplesPerVoxelFace per resolution^2 of surface), then one per
// voxel, their centroid. The samples are never all held at once, so a fine map of a large world
// costs the voxels' memory only. See docs/decisions/point-map-splats.md.
std::vector<Eigen::Vector3f> surfacePointMap(const TriangleMesh& mesh, double resolution, std::uint64_t seed);

// Surface samples per resolution^2 of surface in surfacePointMap: a voxel a surface crosses fully
// is left empty with probability exp(-10), about 5e-5.
inline constexpr double kPointMapSamplesPerVoxelFace = 10.0;

// The number of voxels a surface of area_m2 occupies at most, about, at the given resolution
// (area / resolution^2 for flat surfaces; the bound a scene's resolution is checked against).
double expectedPointMapSize(double area_m2, double resolution);

}  // namespace uampc::world
