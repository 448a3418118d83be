// The per-point loop of rendering a panorama (PanoramicDepthMap, Eq. 5), in two builds: the SSE2
// baseline and AVX2, chosen per process (uampc/simd/dispatch.hpp); both give the same bits, and
// the test compares them. Internal to the library.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "uampc/simd/dispatch.hpp"

namespace uampc::mpc::detail {

// Eq. 5's binning constants of one render.
struct PanoramaProjection {
  float min_range2 = 0.0F, max_range2 = 0.0F;  // squared range window, m^2
  float columns_per_rad = 0.0F, rows_per_rad = 0.0F;
  int width = 0, height = 0;
};

// World to base frame, p_B = R_BW (p_W - r_WB): the translation is removed in double (world
// coordinates far from the origin lose nothing), the rotation applied in float.
struct BaseFrameTransform {
  Eigen::Vector3d r_WB;
  Eigen::Matrix3f R_BW;
};

// Points per binPoints call, at most (its base-frame scratch lives on the stack).
constexpr int kBinBlock = 256;

// Eq. 5 for n <= kBinBlock world points: each one's pixel (column, row) and its range from the
// base origin; row -1 marks a point outside the range window, or NaN (which fails both tests).
void binPoints(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T, const PanoramaProjection& c,
               float* range, std::int32_t* column, std::int32_t* row);
// The same for double points (render(); baseline build only, not a control step's path).
void binPoints(const Eigen::Vector3d* points_W, int n, const BaseFrameTransform& T, const PanoramaProjection& c,
               float* range, std::int32_t* column, std::int32_t* row);

// binPoints' move into the base frame, written once: compiled into each of its builds, and into
// baseFramePoint. Constants are copied into locals and arrays are __restrict: loads through a
// reference or a possible alias keep GCC from vectorising it.
template <class Scalar>
UAMPC_SIMD_INLINE void toBaseFrameBody(const Eigen::Matrix<Scalar, 3, 1>* points_W, int n,
                                       const BaseFrameTransform& T, float* __restrict x, float* __restrict y,
                                       float* __restrict z) {
  const Scalar* __restrict p = points_W->data();  // n packed (x, y, z): a Vector3 has no padding
  const double tx = T.r_WB.x(), ty = T.r_WB.y(), tz = T.r_WB.z();
  const float r00 = T.R_BW(0, 0), r01 = T.R_BW(0, 1), r02 = T.R_BW(0, 2);
  const float r10 = T.R_BW(1, 0), r11 = T.R_BW(1, 1), r12 = T.R_BW(1, 2);
  const float r20 = T.R_BW(2, 0), r21 = T.R_BW(2, 1), r22 = T.R_BW(2, 2);
  for (int j = 0; j < n; ++j) {
    const auto dx = static_cast<float>(static_cast<double>(p[3 * j]) - tx);
    const auto dy = static_cast<float>(static_cast<double>(p[3 * j + 1]) - ty);
    const auto dz = static_cast<float>(static_cast<double>(p[3 * j + 2]) - tz);
    x[j] = r00 * dx + r01 * dy + r02 * dz;
    y[j] = r10 * dx + r11 * dy + r12 * dz;
    z[j] = r20 * dx + r21 * dy + r22 * dz;
  }
}

// One point in the base frame (once per occupied pixel of a render), with the bits binPoints
// binned it by.
template <class Scalar>
Eigen::Vector3f baseFramePoint(const Eigen::Matrix<Scalar, 3, 1>& p_W, const BaseFrameTransform& T) {
  Eigen::Vector3f p_B;
  toBaseFrameBody(&p_W, 1, T, &p_B.x(), &p_B.y(), &p_B.z());
  return p_B;
}

// The two builds, for the test; binPoints calls one of them.
namespace builds {
void binPointsBaseline(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T,
                       const PanoramaProjection& c, float* range, std::int32_t* column, std::int32_t* row);
void binPointsAvx2(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T, const PanoramaProjection& c,
                   float* range, std::int32_t* column, std::int32_t* row);
}  // namespace builds

}  // namespace uampc::mpc::detail
