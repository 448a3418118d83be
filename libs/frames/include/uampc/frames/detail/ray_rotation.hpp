// The arithmetic of PoseKnots::placeRays for a block of rays, in two builds (SSE2 baseline and
// AVX2, uampc/simd/dispatch.hpp) that give the same bits. Internal to uampc_frames and its tests.
#pragma once

namespace uampc::frames::detail {

// A block of rays as structure of arrays, so that the loop over them vectorises: in, each ray's
// blended rotation (quaternion coefficients, not yet normalised) and its direction in the moving
// frame; out, the unit direction in the world, in float.
struct RayBlock {
  static constexpr int kSize = 256;
  alignas(32) double qx[kSize], qy[kSize], qz[kSize], qw[kSize];
  alignas(32) double dx[kSize], dy[kSize], dz[kSize];
  alignas(32) float ux[kSize], uy[kSize], uz[kSize];
};

// For the first n (<= RayBlock::kSize) rays: u = normalised(float(normalised(q) * d)), with the
// operations and their order of Eigen's Quaternion::normalized(), Quaternion * Vector3d and
// Vector3f::normalized() (frames_test compares them bit for bit).
void rotateRays(int n, RayBlock& block);

// The two builds, for the test; rotateRays calls one of them.
namespace builds {
void rotateRaysBaseline(int n, RayBlock& block);
void rotateRaysAvx2(int n, RayBlock& block);
}  // namespace builds

}  // namespace uampc::frames::detail
