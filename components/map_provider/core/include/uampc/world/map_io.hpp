// Loading maps from PCD and PLY files.
//
//   .pcd             -> a point map (fields x, y, z of TYPE F, SIZE 4 or 8, COUNT 1; others
//                       skipped). DATA ascii, binary or binary_compressed, read by our own reader
//                       after the whole file has been checked (docs/decisions/pcd-own-reader.md).
//   .ply with faces  -> a triangle mesh (polygons are split into triangle fans).
//   .ply, no faces   -> a point map.
//                       PLY (ascii, binary either endianness) is read by our own defensive
//                       reader, since pcl::PLYReader 1.13 aborts on some corrupt files.
//
// A point map has no surfaces; the ray-caster gives each point a small sphere (see
// raycaster::RayCastScene), so a point map must be dense enough for rays not to slip through.
// Non-finite points are skipped and counted; triangles that use a skipped vertex or an index out
// of range are dropped and counted. A finite point or vertex more than 1e6 m from the origin
// (coordinate_bound.hpp) is refused, with its line (ASCII) or index (binary). A missing, unreadable, corrupt or empty file throws
// std::runtime_error whose message starts with the file name.
#pragma once

#include <string>
#include <vector>

#include "uampc/world/triangle_mesh.hpp"

namespace uampc::world {

struct MapLoadOptions {
  double voxel_size = 0.0;                           // m; > 0 downsamples point maps (not meshes)
  Eigen::Vector3f offset = Eigen::Vector3f::Zero();  // added to every point and vertex
};

struct LoadedMap {
  TriangleMesh mesh;                    // empty for point maps
  std::vector<Eigen::Vector3f> points;  // empty for meshes
  std::size_t skipped_points = 0;       // non-finite points or vertices
  std::size_t skipped_triangles = 0;    // triangles with a bad vertex or index
  std::vector<std::string> warnings;    // one line per kind of problem met, with counts

  bool isMesh() const { return !mesh.empty(); }
};

LoadedMap loadMap(const std::string& path, const MapLoadOptions& options = {});

// Writers, for tools and tests: PCD of points (binary by default; fields x, y, z as float, read
// back exactly by our reader and PCL's), ASCII PLY of a mesh. Whole or absent: a write that fails
// throws std::runtime_error "cannot write PATH: REASON" and leaves no file cut short
// (run_files::writeTextFile, docs/decisions/run-files-whole-or-absent.md).
enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };
void savePointsPcd(const std::string& path, const std::vector<Eigen::Vector3f>& points,
                   PcdEncoding encoding = PcdEncoding::kBinary);
void saveMeshPly(const std::string& path, const TriangleMesh& mesh);

}  // namespace uampc::world
