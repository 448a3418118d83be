#include "uampc/raycaster/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "uampc/world/seeded_random.hpp"

namespace uampc::raycaster {
namespace {

// The cast direction d turned by the small angles `across` about two axes perpendicular to it.
Eigen::Vector3f reportedDirection(const Eigen::Vector3f& d, const Eigen::Vector2d& across) {
  const Eigen::Vector3f helper = std::abs(d.z()) < 0.9f ? Eigen::Vector3f::UnitZ() : Eigen::Vector3f::UnitX();
  const Eigen::Vector3f e1 = d.cross(helper).normalized();
  const Eigen::Vector3f e2 = d.cross(e1);
  return (d + float(across.x()) * e1 + float(across.y()) * e2).normalized();
}

}  // namespace

RayCaster::RayCaster(const world::TriangleMesh& mesh, const std::vector<Eigen::Vector3f>& points,
                     RayCasterConfig config)
    : config_(std::move(config)), scene_(mesh, points, config_.point_radius), pattern_generator_(config_.model) {
  if (!(config_.model.max_range > config_.model.min_range) || config_.model.min_range < 0.0) {
    throw std::invalid_argument("RayCaster: need 0 <= min_range < max_range");
  }
  if (config_.range_noise_stddev < 0.0 || !(config_.angular_noise_stddev >= 0.0) || config_.dropout_probability < 0.0 ||
      config_.dropout_probability > 1.0) {
    throw std::invalid_argument("RayCaster: noise must be >= 0 and dropout in [0, 1]");
  }
}

namespace {

// The latest time offset of a pattern (s): its points need not come in time order.
double lastTimeOffset(const std::vector<PatternPoint>& points) {
  double last = 0.0;
  for (const PatternPoint& p : points) last = std::max(last, static_cast<double>(p.time_offset));
  return last;
}

}  // namespace

// Each packet holds one laser's (or ring's) next shots, which point almost the same way. In
// firing order a Mid-360 packet holds its 4 lasers' shots, spread over the whole elevation band,
// and Embree's packet traversal visits the union of their paths: 2.8-2.9 ms for a frame's
// intersections against 2.0 grouped (`raycaster_core_bench` BM_SceneIntersectOnly, one core;
// single rays 2.5). Windows of kPacketSize shots per laser keep a packet's shots consecutive in
// time, so the LiDAR has barely moved between them.
std::vector<std::uint32_t> packetOrder(const std::vector<PatternPoint>& points) {
  std::size_t lasers = 1;
  for (const PatternPoint& p : points) lasers = std::max<std::size_t>(lasers, p.ring + std::size_t{1});
  const std::size_t window = RayCastScene::kPacketSize * lasers;
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::uint32_t>(k);
  for (std::size_t first = 0; first < order.size(); first += window) {
    const auto begin = order.begin() + static_cast<std::ptrdiff_t>(first);
    const auto end = order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), first + window));
    std::stable_sort(begin, end, [&](std::uint32_t a, std::uint32_t b) { return points[a].ring < points[b].ring; });
  }
  return order;
}

const std::vector<PatternPoint>& RayCaster::pattern(std::uint64_t frame_index) {
  const bool repeats = config_.model.kind == lidar::ScanPatternKind::kSpinning;
  if (cached_pattern_.empty() || (!repeats && frame_index != cached_frame_)) {
    pattern_generator_.generate(frame_index, cached_pattern_);
    cached_frame_ = frame_index;
    // Our patterns' lasers fire in the same turn every frame (ring = k % lasers): the order is
    // that of the first. (Any permutation gives the same hits; a stale one costs speed only.)
    if (packet_order_.size() != cached_pattern_.size()) packet_order_ = packetOrder(cached_pattern_);
  }
  return cached_pattern_;
}

double RayCaster::lastRayTime(double frame_start, const std::vector<PatternPoint>& points) const {
  return config_.frame_timing == FrameTiming::kSnapshot ? frame_start : frame_start + lastTimeOffset(points);
}

// Eq. 1 per point: the LiDAR's pose in the world at the point's own time,
//   T_WL(t) = T_WB(t) * T_BL(theta(t)),
// exact at knots 0.25 ms apart and interpolated in between (frames/pose_knots.hpp).
void RayCaster::placeContinuousRays(double frame_start, const std::vector<PatternPoint>& points,
                                    const BasePoseAt& base_pose_at, const MotorAngleAt& motor_angle_at) {
  const auto max_range = static_cast<float>(config_.model.max_range);
  lidar_pose_.build(frame_start, lastRayTime(frame_start, points), [&](double t) {
    return base_pose_at(t) * frames::lidarPoseInBase(motor_angle_at(t), config_.calibration);
  });
  lidar_pose_.placeRays(
      points.size(), [&](std::size_t k) { return frame_start + static_cast<double>(points[k].time_offset); },
      [&](std::size_t k) { return points[k].direction; },
      [&](std::size_t k, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
        rays_[k] = {origin, direction, max_range};
      });
}

// Eq. 1 once for the whole frame, at its stamp: the reference simulator renders each frame from
// the latest base pose and one motor angle (its speed_control_opengl_render_node.cpp).
void RayCaster::placeSnapshotRays(double frame_start, const std::vector<PatternPoint>& points,
                                  const BasePoseAt& base_pose_at, const MotorAngleAt& motor_angle_at) {
  const auto max_range = static_cast<float>(config_.model.max_range);
  const Eigen::Isometry3d T_WL =
      base_pose_at(frame_start) * frames::lidarPoseInBase(motor_angle_at(frame_start), config_.calibration);
  const Eigen::Vector3f origin = T_WL.translation().cast<float>();
  const Eigen::Matrix3f R_WL = T_WL.linear().cast<float>();
  for (std::size_t k = 0; k < points.size(); ++k) rays_[k] = {origin, R_WL * points[k].direction, max_range};
}

Scan RayCaster::castFrame(std::uint64_t frame_index, double frame_start, const BasePoseAt& base_pose_at,
                          const MotorAngleAt& motor_angle_at) {
  const std::vector<PatternPoint>& points = pattern(frame_index);
  const auto min_range = static_cast<float>(config_.model.min_range);
  const bool snapshot = config_.frame_timing == FrameTiming::kSnapshot;
  rays_.resize(points.size());
  if (snapshot)
    placeSnapshotRays(frame_start, points, base_pose_at, motor_angle_at);
  else
    placeContinuousRays(frame_start, points, base_pose_at, motor_angle_at);
  if (config_.use_packets) {
    scene_.intersect(rays_, hits_, packet_order_);
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
  const bool blurred = config_.angular_noise_stddev > 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double noise = noisy ? config_.range_noise_stddev * random.normal() : 0.0;
    const bool dropped = lossy && random.chance(config_.dropout_probability);
    Eigen::Vector2d across = Eigen::Vector2d::Zero();
    if (blurred) across = config_.angular_noise_stddev * Eigen::Vector2d(random.normal(), random.normal());
    const Hit& hit = hits_[k];
    if (!hit.valid || hit.distance < min_range || dropped) continue;
    const float range = hit.distance + static_cast<float>(noise);
    if (!(range > 0.0f)) continue;
    ScanPoint p;
    p.position = (blurred ? reportedDirection(points[k].direction, across) : points[k].direction) * range;
    p.intensity = 255.0f * std::abs(hit.normal.dot(rays_[k].direction));
    p.time_offset = snapshot ? 0.0f : points[k].time_offset;
    p.ring = points[k].ring;
    scan.points.push_back(p);
  }
  return scan;
}

Scan RayCaster::castFrame(std::uint64_t frame_index, double frame_start, const world::Trajectory& trajectory,
                          const frames::MotorAngleTrack& motor) {
  const std::vector<PatternPoint>& points = pattern(frame_index);
  const double frame_end = lastRayTime(frame_start, points);
  std::ostringstream msg;
  msg.precision(17);
  if (!trajectory.contains(frame_start) || !trajectory.contains(frame_end)) {
    msg << "RayCaster: trajectory does not cover frame " << frame_index << " [" << frame_start << ", " << frame_end
        << "] s";
    throw std::out_of_range(msg.str());
  }
  if (!motor.covers(frame_start, frame_end)) {
    msg << "RayCaster: motor readings do not cover frame " << frame_index << " [" << frame_start << ", " << frame_end
        << "] s";
    throw std::out_of_range(msg.str());
  }
  return castFrame(
      frame_index, frame_start, [&](double t) { return trajectory.poseAt(t); },
      [&](double t) { return *motor.thetaAt(t); });
}

}  // namespace uampc::raycaster
