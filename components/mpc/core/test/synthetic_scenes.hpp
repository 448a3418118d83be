// Synthetic local maps for the tests and the benchmark: point grids on rectangles.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace uampc::mpc::test {

using Cloud = std::vector<Eigen::Vector3d>;

inline constexpr double kPi = 3.14159265358979323846;

// Points every `spacing` metres on the rectangle origin + a * e1 + b * e2, a in [0, |e1|],
// b in [0, |e2|].
inline void addRectangle(Cloud& cloud, const Eigen::Vector3d& origin, const Eigen::Vector3d& e1,
                         const Eigen::Vector3d& e2, double spacing) {
  const int n1 = static_cast<int>(std::floor(e1.norm() / spacing)) + 1;
  const int n2 = static_cast<int>(std::floor(e2.norm() / spacing)) + 1;
  const Eigen::Vector3d d1 = e1.normalized() * spacing;
  const Eigen::Vector3d d2 = e2.normalized() * spacing;
  for (int i = 0; i < n1; ++i) {
    for (int j = 0; j < n2; ++j) cloud.push_back(origin + i * d1 + j * d2);
  }
}

// A corridor along x from x0 to x1: walls at y = +-half_width, floor at z = floor_z, ceiling at
// z = ceiling_z. No end walls.
inline Cloud corridor(double x0, double x1, double half_width = 2.0, double floor_z = -1.0,
                      double ceiling_z = 2.0, double spacing = 0.1) {
  Cloud cloud;
  const Eigen::Vector3d along(x1 - x0, 0.0, 0.0);
  const double height = ceiling_z - floor_z;
  addRectangle(cloud, {x0, -half_width, floor_z}, along, {0.0, 0.0, height}, spacing);
  addRectangle(cloud, {x0, half_width, floor_z}, along, {0.0, 0.0, height}, spacing);
  addRectangle(cloud, {x0, -half_width, floor_z}, along, {0.0, 2.0 * half_width, 0.0}, spacing);
  addRectangle(cloud, {x0, -half_width, ceiling_z}, along, {0.0, 2.0 * half_width, 0.0}, spacing);
  return cloud;
}

// An end wall across the corridor at x.
inline void addEndWall(Cloud& cloud, double x, double half_width = 2.0, double floor_z = -1.0,
                       double ceiling_z = 2.0, double spacing = 0.1) {
  addRectangle(cloud, {x, -half_width, floor_z}, {0.0, 2.0 * half_width, 0.0},
               {0.0, 0.0, ceiling_z - floor_z}, spacing);
}

}  // namespace uampc::mpc::test
