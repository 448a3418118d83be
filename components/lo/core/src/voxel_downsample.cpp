#include "uampc/lo/voxel_downsample.hpp"

#include <unordered_set>

#include "uampc/lo/voxel.hpp"

namespace uampc::lo {

std::vector<TimedPoint> voxelDownsample(const std::vector<TimedPoint>& points, double voxel_size) {
  if (voxel_size <= 0.0) return points;
  const double inverse = 1.0 / voxel_size;
  std::unordered_set<Voxel, VoxelHash> occupied;
  occupied.reserve(points.size());
  std::vector<TimedPoint> out;
  out.reserve(points.size() / 2);
  for (const TimedPoint& point : points) {
    if (occupied.insert(voxelOf(point.p_B, inverse)).second) out.push_back(point);
  }
  return out;
}

}  // namespace uampc::lo
