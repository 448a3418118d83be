#include "lo_effect.hpp"

#include <algorithm>
#include <vector>

#include "lo_drive.hpp"
#include "simulated_lidar.hpp"
#include "uampc/evaluator/speed_error.hpp"
#include "uampc/raycaster/ray_caster.hpp"

namespace uampc::calibration {

namespace {

constexpr double kEncoderPeriod = 0.005;  // s, 200 Hz

// The encoder of a rotor turning at `speed` from angle 0 at t = 0, as the truth's encoder reads it,
// taken back to rotor angles with the believed rig: what the LO's motor track holds.
frames::MotorAngleTrack believedRotorTrack(double speed, double until, const frames::MotorLidarCalibration& truth,
                                           const frames::MotorLidarCalibration& believed) {
  frames::MotorAngleTrack track(until + 10.0);
  for (double s = 0.0; s <= until; s += kEncoderPeriod) {
    const frames::MotorReading encoder{s, speed * (s - truth.time_offset) + truth.encoder_offset, speed};
    track.add(frames::rotorReading(encoder, believed));
  }
  return track;
}

}  // namespace

LoDriveResult driveLo(const LoDrive& drive, const frames::MotorLidarCalibration& truth,
                      const frames::MotorLidarCalibration& believed) {
  world::WorldSettings settings = tools::worldSettingsFor(drive.source);
  settings.seed = drive.seed;
  const world::World world = world::buildWorld(settings);
  const world::Trajectory& path = world.trajectory;

  raycaster::RayCasterConfig caster_config;
  caster_config.calibration = truth;
  caster_config.range_noise_stddev = drive.range_noise;
  caster_config.seed = drive.seed;
  caster_config.point_radius = world.point_radius;
  raycaster::RayCaster caster(world.mesh, world.points, caster_config);
  const double end = std::min(path.endTime() - 0.2, drive.seconds);
  const frames::MotorAngleTrack rotor = believedRotorTrack(drive.motor_speed, end + 1.0, truth, believed);
  tools::ReplaySettings replay;
  replay.start = caster.frameDuration();  // from the second frame
  replay.end = end;
  replay.rotor_angle = [&drive](double t) { return drive.motor_speed * t; };  // the truth's angle

  lo::OdometryConfig config;
  config.calibration = believed;
  evaluator::AbsoluteTrajectoryError ate;
  std::vector<evaluator::TimedPose> estimates, truths;
  LoDriveResult result;
  tools::driveLo(caster, path, config, rotor, replay, [&](const tools::DrivenFrame& f) {
    ate.add(f.result.time, f.result.T_WB.translation(), f.truth.translation());
    estimates.push_back({f.result.time, f.result.T_WB});
    truths.push_back({f.result.time, f.truth});
    ++result.frames;
  });
  result.ate = ate.rmse();
  result.runaway_at = evaluator::speedError(estimates, truths).first_runaway_time;
  return result;
}

}  // namespace uampc::calibration
