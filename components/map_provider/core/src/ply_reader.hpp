// A small, defensive PLY reader (ascii and binary, either endianness): vertices x, y, z and
// polygon faces. PCL's PLY reader aborts or crashes on some corrupt files; this one checks every
// count and index against the file and throws std::runtime_error instead. Private to world_core.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace uampc::world {

struct PlyContents {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<std::vector<std::uint32_t>> faces;  // vertex indices, as stored (not checked)
};

PlyContents readPly(const std::string& path);

}  // namespace uampc::world
