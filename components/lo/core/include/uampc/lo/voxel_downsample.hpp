// Voxel downsampling of a scan: the first point that falls in each voxel is kept, with its time.
#pragma once

#include <vector>

#include "uampc/lo/scan.hpp"

namespace uampc::lo {

// Keeps a real point (not a centroid) so each kept point keeps its own time for the deskew.
// voxel_size <= 0 returns the input unchanged.
std::vector<TimedPoint> voxelDownsample(const std::vector<TimedPoint>& points, double voxel_size);

}  // namespace uampc::lo
