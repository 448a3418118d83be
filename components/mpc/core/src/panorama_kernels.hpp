// The per-point loops of rendering a panorama (PanoramicDepthMap, Eq. 5), in two builds: the
// SSE2 baseline and AVX2, chosen per process (uampc/simd/dispatch.hpp); both give the same bits,
// and the test compares them. Internal to the library.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace uampc::mpc::detail {

// Eq. 5's binning constants of one render.
struct PanoramaProjection {
  float min_range2 = 0.0F, max_range2 = 0.0F;  // squared range window, m^2
  float columns_per_rad = 0.0F, rows_per_rad = 0.0F;
  int width = 0, height = 0;
};

// The base-frame offset of n world points, p_B = R_BW (p_W - r_WB), as three arrays: the
// translation is removed in double (world coordinates far from the origin lose nothing), the
// rotation applied in float, each coordinate summed left to right. Panorama pixels recompute a
// point with baseFramePoint(), which gives the same bits.
struct BaseFrameTransform {
  Eigen::Vector3d r_WB;
  Eigen::Matrix3f R_BW;
};
void toBaseFrame(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T, float* x, float* y, float* z);
// The same for double points (render(); baseline build only, not a control step's path).
void toBaseFrame(const Eigen::Vector3d* points_W, int n, const BaseFrameTransform& T, float* x, float* y, float* z);

// One point, inline (once per occupied pixel of a render): the operations of toBaseFrame's loop,
// in its order, so the same bits (the test compares them).
template <class Scalar>
Eigen::Vector3f baseFramePoint(const Eigen::Matrix<Scalar, 3, 1>& p_W, const BaseFrameTransform& T) {
  const auto dx = static_cast<float>(static_cast<double>(p_W.x()) - T.r_WB.x());
  const auto dy = static_cast<float>(static_cast<double>(p_W.y()) - T.r_WB.y());
  const auto dz = static_cast<float>(static_cast<double>(p_W.z()) - T.r_WB.z());
  const Eigen::Matrix3f& R = T.R_BW;
  return Eigen::Vector3f(R(0, 0) * dx + R(0, 1) * dy + R(0, 2) * dz, R(1, 0) * dx + R(1, 1) * dy + R(1, 2) * dz,
                         R(2, 0) * dx + R(2, 1) * dy + R(2, 2) * dz);
}

// Pixel (column, row) and range of n base-frame points; row -1 marks a point outside the range
// window, or NaN (which fails both tests).
void project(int n, const float* x, const float* y, const float* z, const PanoramaProjection& c, float* range,
             std::int32_t* column, std::int32_t* row);

// The two builds of each, for the test; the functions above call one of them.
namespace builds {
void toBaseFrameBaseline(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T, float* x, float* y,
                         float* z);
void toBaseFrameAvx2(const Eigen::Vector3f* points_W, int n, const BaseFrameTransform& T, float* x, float* y,
                     float* z);
void projectBaseline(int n, const float* x, const float* y, const float* z, const PanoramaProjection& c,
                     float* range, std::int32_t* column, std::int32_t* row);
void projectAvx2(int n, const float* x, const float* y, const float* z, const PanoramaProjection& c, float* range,
                 std::int32_t* column, std::int32_t* row);
}  // namespace builds

}  // namespace uampc::mpc::detail
