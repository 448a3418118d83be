// The simulated motorized LiDAR: renders one frame of a LiDAR spun by a motor.
//
// Continuous frames (the default): every pattern point is cast at its own time
// t_i = frame_start + time_offset_i, from the pose
//   T_WL(t_i) = T_WB(t_i) * T_BL(theta(t_i)),   T_BL = lidarPoseInBase(theta, calibration)  (Eq. 1)
// so both the base motion and the motor turning during the frame shape the scan. Snapshot frames
// (the paper's reference simulator, docs/results/table-1-reference-regime.md): every point is cast
// from the one pose T_WL(frame_start) and carries time offset 0; the motor still turns between
// frames. The first hit
// within [min_range, max_range] is kept (a nearer hit hides what lies behind, and is dropped if
// closer than min_range, as a real sensor returns nothing then), range noise and dropout are
// applied, and the point is returned in the LiDAR frame at that time.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/frames/pose_knots.hpp"
#include "uampc/lidar/lidar_model.hpp"
#include "uampc/raycaster/ray_cast_scene.hpp"
#include "uampc/raycaster/scan_pattern.hpp"
#include "uampc/world/trajectory.hpp"

namespace uampc::raycaster {

// When a frame's rays are cast: each at its own time (a real spinning or scanning LiDAR), or all
// at the frame's stamp from one pose (the reference simulator's rendered snapshots).
enum class FrameTiming { kContinuous, kSnapshot };

struct RayCasterConfig {
  lidar::LidarModel model = lidar::livoxMid360();
  frames::MotorLidarCalibration calibration = frames::MotorLidarCalibration::referenceRig();
  double range_noise_stddev = 0.0;    // m, Gaussian, added along the ray
  double angular_noise_stddev = 0.0;  // rad, Gaussian, per axis across the ray: the direction a
                                      // return is reported in, not the one it was cast along
  double dropout_probability = 0.0;   // chance that a return is lost
  std::uint64_t seed = 0;             // noise and dropout; frame k uses a seed mixed from (seed, k)
  float point_radius = 0.05f;         // m, splats of point maps (see RayCastScene)
  bool use_packets = true;            // cast in packets (RayCastScene::kPacketSize rays; same result, faster)
  FrameTiming frame_timing = FrameTiming::kContinuous;
};

// One return, in the LiDAR frame at its own time (docs/dev/architecture.md section 4, scan fields).
struct ScanPoint {
  Eigen::Vector3f position;  // m, LiDAR frame
  float intensity = 0.0f;    // 255 * |cos(incidence angle)|
  float time_offset = 0.0f;  // s since the frame start
  std::uint16_t ring = 0;
};

struct Scan {
  double stamp = 0.0;  // s, frame start
  std::uint64_t frame_index = 0;
  std::vector<ScanPoint> points;
  std::size_t rays = 0;  // pattern points cast (returns + misses + dropped)
};

using BasePoseAt = std::function<Eigen::Isometry3d(double t)>;  // T_WB at time t
using MotorAngleAt = std::function<double(double t)>;           // theta at time t (rad)

// The order in which a pattern's rays go to Embree's packets (RayCastScene::intersect): grouped
// by laser (ring), each laser's shots in firing order, in windows of kPacketSize shots per laser.
std::vector<std::uint32_t> packetOrder(const std::vector<PatternPoint>& points);

class RayCaster {
 public:
  RayCaster(const world::TriangleMesh& mesh, const std::vector<Eigen::Vector3f>& points, RayCasterConfig config);
  explicit RayCaster(const world::TriangleMesh& mesh, RayCasterConfig config = {})
      : RayCaster(mesh, {}, std::move(config)) {}

  // Frame number frame_index, starting at frame_start (s). Not thread-safe (one caster per
  // thread; the scene could be shared, the pattern cache cannot).
  Scan castFrame(std::uint64_t frame_index, double frame_start, const BasePoseAt& base_pose_at,
                 const MotorAngleAt& motor_angle_at);

  // Same, from a ground-truth trajectory and the encoder history. Throws std::out_of_range when
  // either does not cover the frame, from frame_start to its last point's time.
  Scan castFrame(std::uint64_t frame_index, double frame_start, const world::Trajectory& trajectory,
                 const frames::MotorAngleTrack& motor);

  double frameDuration() const { return 1.0 / config_.model.frame_rate_hz; }
  const RayCasterConfig& config() const { return config_; }
  const RayCastScene& scene() const { return scene_; }

 private:
  RayCasterConfig config_;
  RayCastScene scene_;
  ScanPatternGenerator pattern_generator_;
  // The pattern of the last frame cast: spinning patterns never change, and a frame is often
  // cast twice (a retry, a test), so this saves regenerating it.
  std::uint64_t cached_frame_ = ~std::uint64_t{0};
  std::vector<PatternPoint> cached_pattern_;
  std::vector<std::uint32_t> packet_order_;  // the rays grouped by laser for Embree's packets
  std::vector<Ray> rays_;         // reused between frames
  frames::PoseKnots lidar_pose_;  // T_WL over the frame being cast
  std::vector<Hit> hits_;
  const std::vector<PatternPoint>& pattern(std::uint64_t frame_index);
  // The time of the frame's last ray: frame_start itself for a snapshot.
  double lastRayTime(double frame_start, const std::vector<PatternPoint>& points) const;
  void placeContinuousRays(double frame_start, const std::vector<PatternPoint>& points, const BasePoseAt& base_pose_at,
                           const MotorAngleAt& motor_angle_at);
  void placeSnapshotRays(double frame_start, const std::vector<PatternPoint>& points, const BasePoseAt& base_pose_at,
                         const MotorAngleAt& motor_angle_at);
};

}  // namespace uampc::raycaster
