// A pose that changes within a frame, evaluated exactly at knots and interpolated in between.
//
// Eq. 1 places every point of a scan with the LiDAR's pose at the point's own time; a frame has
// ~20k points but the pose varies smoothly, so it is evaluated exactly at knots at most
// max_spacing apart (0.25 ms by default: ~400 per 0.1 s frame) and interpolated linearly between
// them (translation lerp, rotation nlerp). Over 0.25 ms the LiDAR turns by at most ~2 mrad (motor
// at 7.2 rad/s plus a fast base), so the interpolation is off by ~1e-8 m and ~1e-8 rad (tested), far
// below the float precision of a scan; exact per-point poses (trajectory interpolation, encoder
// look-up, the motor transform) cost ~15 % of a simulated run.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "uampc/frames/detail/ray_rotation.hpp"

namespace uampc::frames {

class PoseKnots {
 public:
  // Knots over [t0, t1] (t1 >= t0), pose_at(t) -> Eigen::Isometry3d called once per knot, at
  // times within [t0, t1] only.
  template <class PoseAt>
  void build(double t0, double t1, const PoseAt& pose_at, double max_spacing = 2.5e-4) {
    const double span = std::max(0.0, t1 - t0);
    const auto intervals = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(span / max_spacing)));
    t0_ = t0;
    spacing_ = span > 0.0 ? span / static_cast<double>(intervals) : 1.0;
    translations_.resize(intervals + 1);
    rotations_.resize(intervals + 1);
    for (std::size_t j = 0; j <= intervals; ++j) {
      const Eigen::Isometry3d T = pose_at(t0 + std::min(static_cast<double>(j) * spacing_, span));
      translations_[j] = T.translation();
      rotations_[j] = Eigen::Quaterniond(T.linear());
      // Same hemisphere as the previous knot, so that the blend takes the short way.
      if (j > 0 && rotations_[j].coeffs().dot(rotations_[j - 1].coeffs()) < 0.0) rotations_[j].coeffs() *= -1.0;
    }
  }

  // The pose at t; outside [t0, t1] the nearest interval is extended linearly.
  Eigen::Isometry3d operator()(double t) const {
    const Blend b = blendAt(t);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation(b).toRotationMatrix();
    T.translation() = translation(b);
    return T;
  }

  // The same pose applied to the ~20k rays of a frame, without building a rotation matrix per ray:
  // ray k leaves at time_at(k) (s) along direction_at(k) (Eigen::Vector3f, in the moving frame);
  // write(k, origin, direction) gets its origin and unit direction in the world, in float. The
  // rotation's normalisation and the rotated direction's are square roots and divisions per ray,
  // most of the placement's cost, so a block of rays goes through them together, vectorised
  // (detail::rotateRays); the bits are Eigen's (frames_test).
  template <class TimeAt, class DirectionAt, class Write>
  void placeRays(std::size_t n, const TimeAt& time_at, const DirectionAt& direction_at, const Write& write) const {
    detail::RayBlock block;
    Eigen::Vector3f origins[detail::RayBlock::kSize];
    for (std::size_t first = 0; first < n; first += detail::RayBlock::kSize) {
      const int count = static_cast<int>(std::min<std::size_t>(detail::RayBlock::kSize, n - first));
      for (int i = 0; i < count; ++i) {
        const Blend b = blendAt(time_at(first + i));
        const Eigen::Vector4d q = blendedRotation(b);  // (x, y, z, w), not normalised
        block.qx[i] = q.x();
        block.qy[i] = q.y();
        block.qz[i] = q.z();
        block.qw[i] = q.w();
        const Eigen::Vector3d d = direction_at(first + i).template cast<double>();
        block.dx[i] = d.x();
        block.dy[i] = d.y();
        block.dz[i] = d.z();
        origins[i] = translation(b).template cast<float>();
      }
      detail::rotateRays(count, block);
      for (int i = 0; i < count; ++i) {
        write(first + i, origins[i], Eigen::Vector3f(block.ux[i], block.uy[i], block.uz[i]));
      }
    }
  }

  std::size_t size() const { return translations_.size(); }

 private:
  struct Blend {
    std::size_t j;  // interval [j, j + 1]
    double a;       // weight of knot j + 1
  };
  Blend blendAt(double t) const {
    const double u = (t - t0_) / spacing_;
    const std::size_t last = translations_.size() - 2;
    const std::size_t j = u <= 0.0 ? 0 : std::min(static_cast<std::size_t>(u), last);
    return {j, u - static_cast<double>(j)};
  }
  Eigen::Vector4d blendedRotation(const Blend& b) const {
    return (1.0 - b.a) * rotations_[b.j].coeffs() + b.a * rotations_[b.j + 1].coeffs();
  }
  Eigen::Quaterniond rotation(const Blend& b) const { return Eigen::Quaterniond(blendedRotation(b)).normalized(); }
  Eigen::Vector3d translation(const Blend& b) const {
    return (1.0 - b.a) * translations_[b.j] + b.a * translations_[b.j + 1];
  }

  double t0_ = 0.0, spacing_ = 1.0;
  std::vector<Eigen::Vector3d> translations_;
  std::vector<Eigen::Quaterniond> rotations_;
};

}  // namespace uampc::frames
