// The loop the LO studies share (lo_replay, calibration_matrix): the simulated motorized LiDAR
// cast along a world's path, frame by frame, into the LO core started at the ground truth, in one
// process without DDS. What each tool does with a registered frame is its own.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/trajectory.hpp"

namespace uampc::tools {

// One frame the LO registered, with the ground truth at the time its pose refers to.
struct DrivenFrame {
  std::uint64_t index = 0;  // the raycaster's frame number
  const lo::OdometryResult& result;
  const lo::MotorizedLidarOdometry& odometry;  // after the frame: its map, for instance
  Eigen::Isometry3d truth;
  double registration_seconds = 0.0;  // wall time of the LO's registerScan
};

struct ReplaySettings {
  double start = 0.0;  // s: the first frame is the one nearest to start
  double end = 0.0;    // s: the last frame ends at or before end (within the path)
  // The rotor's angle as it truly turns (rad), which the raycaster casts with.
  raycaster::MotorAngleAt rotor_angle;
  // Before each frame is registered, with the frame's end (s): feeds the LO what else it reads
  // (IMU samples). Optional.
  std::function<void(double frame_end, lo::MotorizedLidarOdometry& odometry)> before_frame;
};

// Casts each frame along `truth`, starts the LO (with `config`) at the truth of the first frame's
// end, registers every frame with the motor track `lo_motor` (what the LO's encoder reads) and
// hands it to `on_frame`.
void driveLo(raycaster::RayCaster& caster, const world::Trajectory& truth, lo::OdometryConfig config,
             const frames::MotorAngleTrack& lo_motor, const ReplaySettings& replay,
             const std::function<void(const DrivenFrame&)>& on_frame);

}  // namespace uampc::tools
