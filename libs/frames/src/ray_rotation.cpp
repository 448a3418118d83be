#include "uampc/frames/detail/ray_rotation.hpp"

#include <cmath>

#include "uampc/simd/dispatch.hpp"

namespace uampc::frames::detail {

namespace {

// One ray per iteration, no branches and no calls, so that it vectorises: 2 rays per instruction
// in doubles with SSE2, 4 with AVX2 (the divisions and square roots, most of the cost, included).
// A zero vector is returned as it is, as Eigen's normalized() does: dividing by 1 instead of
// branching keeps the loop straight and gives the same bits.
UAMPC_SIMD_INLINE void rotateBody(int n, RayBlock& b) {
  const double* __restrict qx = b.qx;
  const double* __restrict qy = b.qy;
  const double* __restrict qz = b.qz;
  const double* __restrict qw = b.qw;
  const double* __restrict dx = b.dx;
  const double* __restrict dy = b.dy;
  const double* __restrict dz = b.dz;
  float* __restrict ux = b.ux;
  float* __restrict uy = b.uy;
  float* __restrict uz = b.uz;
  for (int j = 0; j < n; ++j) {
    // Quaternion::normalized(): its squared norm summed as Eigen's two-lane reduction sums
    // (x, y, z, w): (x^2 + z^2) + (y^2 + w^2).
    const double q2 = (qx[j] * qx[j] + qz[j] * qz[j]) + (qy[j] * qy[j] + qw[j] * qw[j]);
    const double q_norm = q2 > 0.0 ? std::sqrt(q2) : 1.0;
    const double x = qx[j] / q_norm, y = qy[j] / q_norm, z = qz[j] / q_norm, w = qw[j] / q_norm;
    // Quaternion * vector as Eigen computes it: uv = 2 (v x d), d + w uv + v x uv.
    double uv_x = y * dz[j] - z * dy[j];
    double uv_y = z * dx[j] - x * dz[j];
    double uv_z = x * dy[j] - y * dx[j];
    uv_x += uv_x;
    uv_y += uv_y;
    uv_z += uv_z;
    const auto rx = static_cast<float>((dx[j] + w * uv_x) + (y * uv_z - z * uv_y));
    const auto ry = static_cast<float>((dy[j] + w * uv_y) + (z * uv_x - x * uv_z));
    const auto rz = static_cast<float>((dz[j] + w * uv_z) + (x * uv_y - y * uv_x));
    // Vector3f::normalized(): Eigen's unrolled reduction sums x^2 + (y^2 + z^2).
    const float r2 = rx * rx + (ry * ry + rz * rz);
    const float r_norm = r2 > 0.0F ? std::sqrt(r2) : 1.0F;
    ux[j] = rx / r_norm;
    uy[j] = ry / r_norm;
    uz[j] = rz / r_norm;
  }
}

}  // namespace

namespace builds {
void rotateRaysBaseline(int n, RayBlock& block) { rotateBody(n, block); }
UAMPC_SIMD_AVX2 void rotateRaysAvx2(int n, RayBlock& block) { rotateBody(n, block); }
}  // namespace builds

void rotateRays(int n, RayBlock& block) {
  if (simd::avx2()) {
    builds::rotateRaysAvx2(n, block);
  } else {
    builds::rotateRaysBaseline(n, block);
  }
}

}  // namespace uampc::frames::detail
