// A recording of a still rig cast by the simulator's core (no DDS): the motor's speed swings so
// that the clock offset shows, the truth is the believed rig composed with a mounting error, and
// the encoder reads the truth's rotor angle with its zero and on its clock (Eq. 1).
#pragma once

#include <cmath>
#include <string>

#include "uampc/calibration/rig_recording.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::calibration::test {

struct SimulatedRig {
  std::string world = "corridor";
  std::string trajectory_file;  // an MCD trajectory: the world generated around it, the rig at its start
  Eigen::Vector3d base_velocity = Eigen::Vector3d::Zero();  // m/s: a base that moves
  double seconds = 4.0;
  double mean_speed = 3.6;    // rad/s
  double speed_swing = 1.5;   // rad/s, amplitude of a 0.5 Hz swing
  double range_noise = 0.02;  // m
  frames::MotorLidarCalibration truth = frames::MotorLidarCalibration::referenceRig();
  bool with_ground_truth = false;
  std::uint64_t seed = 1;
};

// The encoder's angle at time t on its own clock: theta_encoder = theta + encoder_offset.
inline double encoderAngle(const SimulatedRig& rig, double t) {
  const double w = M_PI;  // 0.5 Hz
  return rig.mean_speed * t + rig.speed_swing / w * (1.0 - std::cos(w * t)) + rig.truth.encoder_offset;
}
inline double encoderRate(const SimulatedRig& rig, double t) {
  return rig.mean_speed + rig.speed_swing * std::sin(M_PI * t);
}

inline RigRecording simulatedRecording(const SimulatedRig& rig) {
  world::WorldSettings settings;
  settings.world = rig.world;
  if (!rig.trajectory_file.empty()) {  // as config/scenes/base/mcd_sequence.yaml
    settings.world = "around_trajectory";
    settings.trajectory = "file";
    settings.trajectory_file = rig.trajectory_file;
    settings.interpolation = "smooth";
    settings.smoothing = 0.5;
  }
  const world::World world = world::buildWorld(settings);
  raycaster::RayCasterConfig config;
  config.calibration = rig.truth;
  config.range_noise_stddev = rig.range_noise;
  config.seed = rig.seed;
  raycaster::RayCaster caster(world.mesh, world.points, config);
  // The rig stands where the world's path starts (and moves from there when asked).
  const Eigen::Isometry3d start = world.trajectory.poseAt(0.0);
  auto base_at = [&](double t) {
    Eigen::Isometry3d T = start;
    T.translation() += rig.base_velocity * t;
    return T;
  };
  // A point stamped t (the LiDAR's clock) sees the rotor where the encoder read at t + time_offset.
  auto rotor_at = [&](double t) { return encoderAngle(rig, t + rig.truth.time_offset) - rig.truth.encoder_offset; };
  RigRecording recording;
  for (double t = 0.0; t <= rig.seconds + 0.2; t += 0.005)
    recording.encoder.push_back({t, encoderAngle(rig, t), encoderRate(rig, t)});
  const double period = caster.frameDuration();
  for (std::uint64_t k = 1; (static_cast<double>(k) + 1.0) * period < rig.seconds; ++k) {
    const raycaster::Scan scan = caster.castFrame(k, static_cast<double>(k) * period, base_at, rotor_at);
    RecordedScan recorded;
    recorded.stamp = scan.stamp;
    for (const auto& p : scan.points) {
      recorded.points.push_back(p.position);
      recorded.time_offsets.push_back(p.time_offset);
    }
    recording.scans.push_back(std::move(recorded));
    if (rig.with_ground_truth) recording.base_poses.push_back({scan.stamp, base_at(scan.stamp)});
  }
  return recording;
}

}  // namespace uampc::calibration::test
