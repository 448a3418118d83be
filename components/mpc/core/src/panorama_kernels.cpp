#include "panorama_kernels.hpp"

#include <algorithm>
#include <cmath>

#include "angles.hpp"
#include "fast_atan2.hpp"

namespace uampc::mpc::detail {

namespace {

// Eq. 5 without branches (selects), so that it vectorises (locals and __restrict: see
// toBaseFrameBody).
UAMPC_SIMD_INLINE void projectBody(int n, const float* __restrict x, const float* __restrict y,
                                   const float* __restrict z, const PanoramaProjection& c, float* __restrict range,
                                   std::int32_t* __restrict column, std::int32_t* __restrict row) {
  constexpr float kPiF = static_cast<float>(kPi);
  const float min2 = c.min_range2, max2 = c.max_range2;
  const float columns_per_rad = c.columns_per_rad, rows_per_rad = c.rows_per_rad;
  const int width = c.width, last_row = c.height - 1;
  for (int j = 0; j < n; ++j) {
    const float horizontal2 = x[j] * x[j] + y[j] * y[j];
    const float r2 = horizontal2 + z[j] * z[j];
    // asin(z / r) is computed as atan2(z, sqrt(x^2 + y^2)), the same angle.
    const float azimuth = fastAtan2(y[j], x[j]);
    const float elevation = fastAtan2(z[j], std::sqrt(horizontal2));
    int u = static_cast<int>((azimuth + kPiF) * columns_per_rad);  // >= 0: truncation = floor
    u = u >= width ? u - width : u;                                 // azimuth == +pi
    const int v = static_cast<int>((0.5F * kPiF - elevation) * rows_per_rad);
    column[j] = u;
    range[j] = std::sqrt(r2);
    row[j] = (r2 >= min2 && r2 <= max2) ? std::min(v, last_row) : -1;
  }
}

// Into the base frame as structure-of-arrays, then binned: both loops vectorise.
template <class Scalar>
UAMPC_SIMD_INLINE void binBody(const Eigen::Matrix<Scalar, 3, 1>* points_W, int n, const BaseFrameTransform& T,
                               const PanoramaProjection& c, float* range, std::int32_t* column, std::int32_t* row) {
  float x[kBinBlock], y[kBinBlock], z[kBinBlock];
  toBaseFrameBody(points_W, n, T, x, y, z);
  projectBody(n, x, y, z, c, range, column, row);
}

}  // namespace

namespace builds {
void binPointsBaseline(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T,
                       const PanoramaProjection& c, float* range, std::int32_t* column, std::int32_t* row) {
  binBody(points_W, n, T, c, range, column, row);
}
UAMPC_SIMD_AVX2 void binPointsAvx2(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T,
                                   const PanoramaProjection& c, float* range, std::int32_t* column,
                                   std::int32_t* row) {
  binBody(points_W, n, T, c, range, column, row);
}
}  // namespace builds

void binPoints(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T, const PanoramaProjection& c,
               float* range, std::int32_t* column, std::int32_t* row) {
  if (simd::avx2()) {
    builds::binPointsAvx2(points_W, n, T, c, range, column, row);
  } else {
    builds::binPointsBaseline(points_W, n, T, c, range, column, row);
  }
}

void binPoints(const Eigen::Vector3d* points_W, int n, const BaseFrameTransform& T, const PanoramaProjection& c,
               float* range, std::int32_t* column, std::int32_t* row) {
  binBody(points_W, n, T, c, range, column, row);
}

}  // namespace uampc::mpc::detail
