#include "uampc/evaluator/voxel_octree.hpp"

#include <octomap/OcTree.h>

#include <sstream>
#include <stdexcept>

#include "uampc/run_files/text_file.hpp"

namespace uampc::evaluator {

namespace {

constexpr int kCenterKey = 32768;  // OctoMap's tree_max_val for its 16-level trees
constexpr int kTreeDepth = 16;

bool inKeyRange(int index) { return index >= -kCenterKey && index < kCenterKey; }

}  // namespace

std::size_t writeVoxelOctree(const std::string& path, const std::vector<Eigen::Vector3i>& voxels,
                             double resolution) {
  octomap::OcTree tree(resolution);
  std::size_t written = 0;
  for (const Eigen::Vector3i& v : voxels) {
    if (!inKeyRange(v.x()) || !inKeyRange(v.y()) || !inKeyRange(v.z())) continue;
    const octomap::OcTreeKey key(static_cast<octomap::key_type>(v.x() + kCenterKey),
                                 static_cast<octomap::key_type>(v.y() + kCenterKey),
                                 static_cast<octomap::key_type>(v.z() + kCenterKey));
    // Straight to the clamping maximum: one scan of the voxel is enough to call it scanned.
    tree.updateNode(key, tree.getClampingThresMaxLog(), /*lazy_eval=*/true);
    ++written;
  }
  tree.updateInnerOccupancy();
  // writeBinary converts to maximum likelihood and prunes before writing. Into memory first:
  // OctoMap's file overload answers true whatever its stream's state, so a full disk would pass
  // unseen; writeTextFile checks every byte and leaves the file whole or absent.
  std::ostringstream bytes(std::ios::binary);
  if (!tree.writeBinary(bytes)) throw std::runtime_error("cannot encode octree file " + path);
  run_files::writeTextFile(path, bytes.str());
  return written;
}

VoxelOctree readVoxelOctree(const std::string& path) {
  octomap::OcTree tree(0.1);  // the file sets the resolution
  if (!tree.readBinary(path)) {
    throw std::runtime_error("cannot read octree file " + path);
  }
  VoxelOctree result;
  result.resolution = tree.getResolution();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    // A pruned leaf at depth d stands for 2^(16-d) voxels along each axis from its corner key.
    const octomap::OcTreeKey corner = it.getIndexKey();
    const int side = 1 << (kTreeDepth - static_cast<int>(it.getDepth()));
    for (int dx = 0; dx < side; ++dx) {
      for (int dy = 0; dy < side; ++dy) {
        for (int dz = 0; dz < side; ++dz) {
          result.voxels.emplace_back(corner[0] + dx - kCenterKey, corner[1] + dy - kCenterKey,
                                     corner[2] + dz - kCenterKey);
        }
      }
    }
  }
  return result;
}

}  // namespace uampc::evaluator
