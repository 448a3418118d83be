// Thinning a scan before registration: one point per voxel, then (optionally) at most a budget of
// points spread evenly over space.
#pragma once

#include <cstddef>
#include <vector>

#include "uampc/lo/scan.hpp"

namespace uampc::lo {

// Voxel downsampling: the first point that falls in each voxel is kept, with its time. Keeps a
// real point (not a centroid) so each kept point keeps its own time for the deskew.
// voxel_size <= 0 returns the input unchanged.
std::vector<TimedPoint> voxelDownsample(const std::vector<TimedPoint>& points, double voxel_size);

// The points sorted by the Morton (Z-order) code of their voxel (cell_size): points near in space
// are near in the result. A copy, not pointers, so that loops over it read memory in order.
std::vector<TimedPoint> spatialOrder(const std::vector<TimedPoint>& points, double cell_size);

// At most max_points of the points, spread evenly over space: in spatial order (cell_size), every
// (size / max_points)-th point. Each region keeps its share of the points, so a frame's rare
// features (a corridor's end wall) keep theirs; a frame within the budget is returned whole and
// unchanged (moved through, not copied: the LO's every frame without a budget). The registration
// budget of the LO (OdometryConfig::max_registration_points), as KISS-ICP and FAST-LIO2 register a
// few thousand points a frame. max_points 0: no budget.
std::vector<TimedPoint> spatialSubset(std::vector<TimedPoint> points, std::size_t max_points, double cell_size);

}  // namespace uampc::lo
