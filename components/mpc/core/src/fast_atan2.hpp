// atan2 by a minimax polynomial, for binning points into panorama pixels.
//
// std::atan2 is the dominant cost of rendering a 100k-point panorama (two calls per point). This
// approximation has a maximum error below 1e-5 rad, three orders of magnitude under a 1-degree
// pixel. It is written without branches: the octant tests of a naive version are unpredictable
// for a point cloud and their mispredictions cost more than the arithmetic. Internal to the library.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace uampc::mpc::detail {

inline double fastAtan2(double y, double x) {
  constexpr double kPi = 3.14159265358979323846;
  const double ax = std::abs(x);
  const double ay = std::abs(y);
  const double a = std::min(ax, ay) / std::max(std::max(ax, ay), std::numeric_limits<double>::min());
  const double s = a * a;
  // atan(a) on [0, 1], odd minimax polynomial of degree 11.
  double r = a * (0.99997726 +
                  s * (-0.33262347 +
                       s * (0.19354346 + s * (-0.11643287 + s * (0.05265332 + s * -0.01172120)))));
  const double swapped = static_cast<double>(ay > ax);  // r = pi/2 - r
  r += swapped * (0.5 * kPi - 2.0 * r);
  const double negative_x = static_cast<double>(x < 0.0);  // r = pi - r
  r += negative_x * (kPi - 2.0 * r);
  return std::copysign(r, y);
}

}  // namespace uampc::mpc::detail
