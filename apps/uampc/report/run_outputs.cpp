#include "report/run_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "uampc/evaluator/tum_trajectory.hpp"
#include "uampc/evaluator/voxel_octree.hpp"

namespace uampc::app {

TrajectoryXY readTumPositions(const std::string& path) {
  TrajectoryXY out;
  if (!std::filesystem::is_regular_file(path)) return out;
  for (const evaluator::TimedPose& pose : evaluator::readTumTrajectory(path)) {
    out.t.push_back(pose.time);
    out.x.push_back(pose.pose.translation().x());
    out.y.push_back(pose.pose.translation().y());
  }
  return out;
}

Footprint readVoxelFootprint(const std::string& path, double min_cell, int max_cells_across) {
  Footprint out;
  if (!std::filesystem::is_regular_file(path)) return out;
  const evaluator::VoxelOctree octree = evaluator::readVoxelOctree(path);
  if (octree.voxels.empty() || octree.resolution <= 0) return out;
  int lo = octree.voxels.front().x(), hi = lo;
  for (const auto& v : octree.voxels) {
    lo = std::min({lo, v.x(), v.y()});
    hi = std::max({hi, v.x(), v.y()});
  }
  // Whole voxels per cell, so that every voxel falls into exactly one cell.
  const double wanted = std::max(min_cell / octree.resolution, static_cast<double>(hi - lo + 1) / max_cells_across);
  const int merge = std::max(1, static_cast<int>(std::ceil(wanted - 1e-9)));
  out.cell = merge * octree.resolution;
  std::map<std::pair<int, int>, int> columns;
  auto cellOf = [merge](int v) { return static_cast<int>(std::floor(static_cast<double>(v) / merge)); };
  for (const auto& v : octree.voxels) ++columns[{cellOf(v.x()), cellOf(v.y())}];
  for (const auto& [key, count] : columns) {
    out.x.push_back(key.first * out.cell);
    out.y.push_back(key.second * out.cell);
    out.count.push_back(count);
  }
  return out;
}

}  // namespace uampc::app
