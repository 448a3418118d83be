// PCD files read and written by uampc's own code (docs/decisions/pcd-own-reader.md): the points of
// fields x, y, z (TYPE F, SIZE 4 or 8, COUNT 1; other fields skipped) from DATA ascii, binary or
// binary_compressed. The whole file is checked first; a file PCL 1.13 would misread is refused.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace uampc::world {

// The points of the PCD file `path` whose contents are `bytes`, in file order, non-finite ones
// included (as NaN or infinity). A corrupt file, one without usable x, y, z fields, or a finite
// point beyond the coordinate bound (coordinate_bound.hpp) throws std::runtime_error starting
// with `path`.
std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path, const std::string& bytes);

}  // namespace uampc::world
