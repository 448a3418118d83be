#include "uampc/raycaster/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "uampc/world/seeded_random.hpp"

namespace uampc::raycaster {

RayCaster::RayCaster(const world::TriangleMesh& mesh, const std::vector<Eigen::Vector3f>& points,
                     RayCasterConfig config)
    : config_(std::move(config)), scene_(mesh, points, config_.point_radius) {
  if (!(config_.model.max_range > config_.model.min_range) || config_.model.min_range < 0.0) {
    throw std::invalid_argument("RayCaster: need 0 <= min_range < max_range");
  }
  if (config_.range_noise_stddev < 0.0 || config_.dropout_probability < 0.0 ||
      config_.dropout_probability > 1.0) {
    throw std::invalid_argument("RayCaster: noise must be >= 0 and dropout in [0, 1]");
  }
}

const std::vector<PatternPoint>& RayCaster::pattern(std::uint64_t frame_index) {
  const bool repeats = config_.model.kind == ScanPatternKind::kSpinning;
  if (cached_pattern_.empty() || (!repeats && frame_index != cached_frame_)) {
    cached_pattern_ = scanPattern(config_.model, frame_index);
    cached_frame_ = frame_index;
  }
  return cached_pattern_;
}

Scan RayCaster::castFrame(std::uint64_t frame_index, double frame_start,
                          const BasePoseAt& base_pose_at, const MotorAngleAt& motor_angle_at) {
  const std::vector<PatternPoint>& points = pattern(frame_index);
  const auto max_range = static_cast<float>(config_.model.max_range);
  const auto min_range = static_cast<float>(config_.model.min_range);

  // Eq. 1 per point: the LiDAR's pose in the world at the point's own time,
  //   T_WL(t) = T_WB(t) * T_BL(theta(t)).
  // It is evaluated exactly at knots kKnotSpacing apart and interpolated linearly in between
  // (origin lerp, rotation nlerp): over <= 0.25 ms the LiDAR turns by at most ~2 mrad (motor at
  // 7.2 rad/s plus a fast base), so the interpolation is off by < 1e-8 m and < 1e-9 rad, far below
  // the float precision of the output, and a frame needs ~400 exact poses instead of one per ray
  // (trajectory interpolation, encoder look-up and the motor transform were ~15 % of a run).
  // The knots span exactly [frame_start, last point's time]: the pose sources need not cover more.
  constexpr double kMaxKnotSpacing = 2.5e-4;  // s
  double last_offset = 0.0;
  for (const PatternPoint& p : points) last_offset = std::max(last_offset, static_cast<double>(p.time_offset));
  const auto intervals = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(last_offset / kMaxKnotSpacing)));
  const double spacing = last_offset > 0.0 ? last_offset / static_cast<double>(intervals) : 1.0;
  const std::size_t knots = intervals + 1;
  knot_origins_.resize(knots);
  knot_rotations_.resize(knots);
  for (std::size_t j = 0; j < knots; ++j) {
    const double t = frame_start + std::min(static_cast<double>(j) * spacing, last_offset);
    const Eigen::Isometry3d T_WL = base_pose_at(t) * frames::lidarPoseInBase(motor_angle_at(t), config_.calibration);
    knot_origins_[j] = T_WL.translation();
    knot_rotations_[j] = Eigen::Quaterniond(T_WL.linear());
    // Same hemisphere as the previous knot, so that the blend takes the short way.
    if (j > 0 && knot_rotations_[j].coeffs().dot(knot_rotations_[j - 1].coeffs()) < 0.0) {
      knot_rotations_[j].coeffs() *= -1.0;
    }
  }
  rays_.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double u = static_cast<double>(points[k].time_offset) / spacing;
    const auto j = std::min(static_cast<std::size_t>(std::max(u, 0.0)), knots - 2);
    const double a = u - static_cast<double>(j);
    const Eigen::Vector3d origin = (1.0 - a) * knot_origins_[j] + a * knot_origins_[j + 1];
    Eigen::Quaterniond q;
    q.coeffs() = (1.0 - a) * knot_rotations_[j].coeffs() + a * knot_rotations_[j + 1].coeffs();
    q.normalize();
    rays_[k].origin = origin.cast<float>();
    rays_[k].direction = (q * points[k].direction.cast<double>()).normalized().cast<float>();
    rays_[k].max_distance = max_range;
  }
  if (config_.use_packets) {
    scene_.intersect(rays_, hits_);
  } else {
    hits_.resize(rays_.size());
    for (std::size_t k = 0; k < rays_.size(); ++k) hits_[k] = scene_.intersect(rays_[k]);
  }

  Scan scan;
  scan.stamp = frame_start;
  scan.frame_index = frame_index;
  scan.rays = points.size();
  scan.points.reserve(points.size());
  // Noise and dropout are drawn for every ray in order, hit or not, so a frame's random numbers
  // do not depend on what the world looks like.
  world::SeededRandom random(world::mixSeed(config_.seed, frame_index));
  const bool noisy = config_.range_noise_stddev > 0.0;
  const bool lossy = config_.dropout_probability > 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double noise = noisy ? config_.range_noise_stddev * random.normal() : 0.0;
    const bool dropped = lossy && random.chance(config_.dropout_probability);
    const Hit& hit = hits_[k];
    if (!hit.valid || hit.distance < min_range || dropped) continue;
    const float range = hit.distance + static_cast<float>(noise);
    if (!(range > 0.0f)) continue;
    ScanPoint p;
    p.position = points[k].direction * range;
    p.intensity = 255.0f * std::abs(hit.normal.dot(rays_[k].direction));
    p.time_offset = points[k].time_offset;
    p.ring = points[k].ring;
    scan.points.push_back(p);
  }
  return scan;
}

Scan RayCaster::castFrame(std::uint64_t frame_index, double frame_start,
                          const world::Trajectory& trajectory,
                          const frames::MotorAngleTrack& motor) {
  const std::vector<PatternPoint>& points = pattern(frame_index);
  const double frame_end =
      frame_start + (points.empty() ? 0.0 : static_cast<double>(points.back().time_offset));
  std::ostringstream msg;
  msg.precision(17);
  if (!trajectory.contains(frame_start) || !trajectory.contains(frame_end)) {
    msg << "RayCaster: trajectory does not cover frame " << frame_index << " [" << frame_start
        << ", " << frame_end << "] s";
    throw std::out_of_range(msg.str());
  }
  if (!motor.covers(frame_start, frame_end)) {
    msg << "RayCaster: motor readings do not cover frame " << frame_index << " [" << frame_start
        << ", " << frame_end << "] s";
    throw std::out_of_range(msg.str());
  }
  return castFrame(
      frame_index, frame_start, [&](double t) { return trajectory.poseAt(t); },
      [&](double t) { return *motor.thetaAt(t); });
}

}  // namespace uampc::raycaster
