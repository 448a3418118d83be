// Map files: PCD read and written by our own code (pcd_reader.cpp, pcd_writer.cpp), PLY read by
// our own reader (ply_reader.cpp); docs/decisions/pcd-own-reader.md, ply-own-reader.md.
#include "uampc/world/map_io.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pcd_reader.hpp"
#include "ply_reader.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/world/coordinate_bound.hpp"
#include "uampc/world/point_sampling.hpp"

namespace uampc::world {
namespace {

std::string extensionOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void keepFinitePoints(std::vector<Eigen::Vector3f>& points, LoadedMap& map) {
  const auto end =
      std::remove_if(points.begin(), points.end(), [](const Eigen::Vector3f& p) { return !p.allFinite(); });
  const auto skipped = static_cast<std::size_t>(points.end() - end);
  points.erase(end, points.end());
  if (skipped > 0) {
    map.skipped_points += skipped;
    map.warnings.push_back(std::to_string(skipped) + " non-finite points skipped");
  }
}

void loadPcd(const std::string& path, LoadedMap& map) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  map.points = readPcdPoints(path, bytes);
  keepFinitePoints(map.points, map);
}

void loadPly(const std::string& path, LoadedMap& map) {
  PlyContents ply = readPly(path);
  if (ply.faces.empty()) {
    map.points = std::move(ply.vertices);
    keepFinitePoints(map.points, map);
    return;
  }
  // A mesh: vertices stay in place (indices!), bad ones only disqualify their triangles.
  std::vector<Eigen::Vector3f>& vertices = ply.vertices;
  std::size_t bad_vertices = 0;
  for (const auto& v : vertices) bad_vertices += v.allFinite() ? 0 : 1;
  std::size_t bad_triangles = 0;
  const auto n = static_cast<std::uint32_t>(vertices.size());
  for (const auto& idx : ply.faces) {
    if (idx.size() < 3) {
      ++bad_triangles;
      continue;
    }
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) {  // fan
      const std::uint32_t a = idx[0], b = idx[k], c = idx[k + 1];
      if (a >= n || b >= n || c >= n || !vertices[a].allFinite() || !vertices[b].allFinite() ||
          !vertices[c].allFinite()) {
        ++bad_triangles;
        continue;
      }
      map.mesh.triangles.emplace_back(a, b, c);
    }
  }
  for (auto& v : vertices) {
    if (!v.allFinite()) v.setZero();  // used by no kept triangle
  }
  map.mesh.vertices = std::move(vertices);
  if (bad_vertices > 0) {
    map.skipped_points = bad_vertices;
    map.warnings.push_back(std::to_string(bad_vertices) + " non-finite vertices");
  }
  if (bad_triangles > 0) {
    map.skipped_triangles = bad_triangles;
    map.warnings.push_back(std::to_string(bad_triangles) +
                           " faces dropped (bad vertex, index out of range, or fewer than 3)");
  }
}

}  // namespace

LoadedMap loadMap(const std::string& path, const MapLoadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error(path + ": no such map file");
  }
  if (std::filesystem::file_size(path, ec) == 0) throw std::runtime_error(path + ": empty file");
  if (!withinCoordinateBound(options.offset)) {
    throw std::runtime_error(path + ": the map's offset " + beyondBoundText(options.offset));
  }
  LoadedMap map;
  const std::string ext = extensionOf(path);
  try {
    if (ext == ".pcd") {
      loadPcd(path, map);
    } else if (ext == ".ply") {
      loadPly(path, map);
    } else {
      throw std::runtime_error(path + ": unknown map format '" + ext + "' (expected .pcd or .ply)");
    }
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::exception& e) {  // bad_alloc on a map beyond the machine's memory, ...
    throw std::runtime_error(path + ": cannot read map: " + e.what());
  }
  if (map.mesh.empty() && map.points.empty()) {
    throw std::runtime_error(path + ": map holds no usable points or triangles");
  }
  map.points = voxelDownsample(map.points, options.voxel_size);
  for (auto& p : map.points) p += options.offset;
  for (auto& v : map.mesh.vertices) v += options.offset;
  return map;
}

void saveMeshPly(const std::string& path, const TriangleMesh& mesh) {
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  out.precision(9);
  for (const auto& v : mesh.vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : mesh.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  run_files::writeTextFile(path, out.str());  // whole or absent
}

}  // namespace uampc::world
