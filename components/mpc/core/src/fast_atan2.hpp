// atan2 by a minimax polynomial, for binning points into panorama pixels.
//
// std::atan2 is the dominant cost of rendering a 100k-point panorama (two calls per point). This
// approximation has a maximum error below 1e-5 rad, three orders of magnitude under a 1-degree
// pixel. It is written without branches, as selects: the octant tests of a naive version are
// unpredictable for a point cloud, and selects let the compiler vectorise a loop that calls it
// (SSE2 baseline, 4 floats per instruction). Internal to the library.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace uampc::mpc::detail {

template <typename T>
inline T fastAtan2(T y, T x) {
  constexpr T kPi = T(3.14159265358979323846);
  const T ax = std::abs(x);
  const T ay = std::abs(y);
  const T a = std::min(ax, ay) / std::max(std::max(ax, ay), std::numeric_limits<T>::min());
  const T s = a * a;
  // atan(a) on [0, 1], odd minimax polynomial of degree 11.
  T r = a * (T(0.99997726) +
             s * (T(-0.33262347) +
                  s * (T(0.19354346) +
                       s * (T(-0.11643287) + s * (T(0.05265332) + s * T(-0.01172120))))));
  r = ay > ax ? T(0.5) * kPi - r : r;  // octant swap
  r = x < T(0) ? kPi - r : r;          // left half-plane
  return std::copysign(r, y);
}

}  // namespace uampc::mpc::detail
