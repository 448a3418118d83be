#include "lo_drive.hpp"

#include <chrono>
#include <cmath>

#include "simulated_lidar.hpp"

namespace uampc::tools {

void driveLo(raycaster::RayCaster& caster, const world::Trajectory& truth, lo::OdometryConfig config,
             const frames::MotorAngleTrack& lo_motor, const ReplaySettings& replay,
             const std::function<void(const DrivenFrame&)>& on_frame) {
  const double frame = caster.frameDuration();
  const auto base_at = [&truth](double t) { return truth.poseAt(t); };
  lo::MotorizedLidarOdometry odometry;  // replaced once the first frame's end is known
  bool started = false;
  auto k = static_cast<std::uint64_t>(std::llround(replay.start / frame));
  for (double t0 = static_cast<double>(k) * frame; t0 + frame <= replay.end; t0 = static_cast<double>(++k) * frame) {
    const lo::Scan scan = toOdometryScan(caster.castFrame(k, t0, base_at, replay.rotor_angle));
    if (!started) {
      startAtTruth(config, truth, scanEndTime(scan));
      odometry = lo::MotorizedLidarOdometry(config);
      started = true;
    }
    if (replay.before_frame) replay.before_frame(t0 + frame, odometry);
    const auto registration_start = std::chrono::steady_clock::now();
    const lo::OdometryResult result = odometry.registerScan(scan, lo_motor);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - registration_start).count();
    on_frame(DrivenFrame{k, result, odometry, truth.poseAt(result.time), seconds});
  }
}

}  // namespace uampc::tools
