// lo_replay: the simulated motorized LiDAR and the LO in one process, without DDS, to study the
// LO on a trajectory quickly (a development tool: the scenes run the real components over DDS).
//
//   lo_replay (TRAJECTORY.csv | corridor | multilevel | campus) [--start S] [--duration S]
//             [--motor RAD_PER_S] [--lidar MODEL] [--seed N] [--every N] [--set GROUP.NAME=VALUE ...]
//
// --set takes the components' own parameters, with their defaults and bounds (uampc components
// lists them): lo.* the LO's (lo_parameters.hpp), world.* map_provider's world and trajectory
// (world_parameters.hpp), lidar.* the raycaster's noise (scan_parameters.hpp). Builds the world as
// map_provider does (world::buildWorld): for an MCD trajectory the world generated around it
// (attitude turned z-up, 0.5 s smoothing, smooth interpolation, as the MCD scenes); for a
// procedural world its generated path at 1.5 m/s; any of them as a point map with
// world.point_map_resolution. Spins the motor at a constant speed, casts the frames of the LiDAR model
// (--lidar, as a scene's rig.lidar_model; the Mid-360 by default) with the reference rig's tilt
// (exact ranges unless --set lidar.range_noise=M; the scenes have 2 cm), registers them, and prints per frame the
// rotation and position error against ground truth, the estimated and true yaw rate, and the LO's figures
// (`pts`: points the LO kept after its downsampling; `v_err`: the velocity's error, m/s; `nd`:
// degenerate directions of the 12-dimensional state; the weakest pose direction, rotation scaled
// at 10 m); then a summary line (with the evaluator's runaway test, speed_error.hpp).
// --set lo.use_imu=true simulates the Mid-360's IMU (the
// raycaster's simulator) and runs the LO LiDAR-inertial. LO_REPLAY_DEBUG=T prints every
// eigenvalue, the velocities and their standard deviations from T s on.
#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "lo_drive.hpp"
#include "lo_parameters.hpp"
#include "parameter_overrides.hpp"
#include "scan_parameters.hpp"
#include "simulated_lidar.hpp"
#include "tool_main.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/evaluator/speed_error.hpp"
#include "uampc/lidar/lidar_model.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/raycaster/imu_simulator.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/world_source.hpp"
#include "world_parameters.hpp"

using namespace uampc;

namespace {

double degrees(double rad) { return rad * 180.0 / M_PI; }

}  // namespace

int replay(int argc, char** argv);

int main(int argc, char** argv) { return tools::runTool("lo_replay", replay, argc, argv); }

int replay(int argc, char** argv) {
  CLI::App app{
      "Replays the simulated motorized LiDAR at a constant motor speed into the LO, without DDS, and prints per\n"
      "frame the errors against ground truth, then a summary line (docs/dev/testing.md, \"Development tools\").",
      "lo_replay"};
  std::string source;
  double start = 0.0, duration = 30.0, motor_speed = 3.6;
  std::uint64_t seed = 1;
  int every = 1;
  std::string lidar_name = "livox_mid360";
  std::vector<std::string> assignments;
  app.add_option("SOURCE", source, "an MCD trajectory (.csv), or corridor, multilevel or campus")->required();
  app.add_option("--start", start, "s of the trajectory skipped")
      ->check(command_line::kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--duration", duration, "s replayed")->check(command_line::kFiniteNonNegative)->capture_default_str();
  app.add_option("--motor", motor_speed, "constant motor speed, rad/s")
      ->check(command_line::kFinite)
      ->capture_default_str();
  app.add_option("--lidar", lidar_name, "the LiDAR model on the motor, as a scene's rig.lidar_model")
      ->check(CLI::IsMember({"livox_mid360", "livox_avia", "velodyne_vlp16"}))
      ->capture_default_str();
  app.add_option("--seed", seed, "the world's and the noise's seed")->capture_default_str();
  app.add_option("--every", every, "print every N-th frame (and every frame more than 1 degree off)")
      ->check(command_line::kPositiveCount)
      ->capture_default_str();
  app.add_option("--set", assignments,
                 "a component's parameter, as in a scene: lo.NAME, world.NAME or lidar.NAME (uampc components "
                 "lists them)")
      ->type_name(tools::ParameterOverrides::kSyntax);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  world::WorldSettings settings = tools::worldSettingsFor(source);
  settings.seed = seed;
  lo::OdometryConfig config;
  raycaster::RayCasterConfig caster_config;  // exact casts unless --set lidar.range_noise=M (scenes: 0.02)
  caster_config.model = lidar::lidarModelByName(lidar_name);
  try {
    tools::ParameterOverrides set(assignments);
    set.apply("lo", bindLoParameters, config);
    set.apply("world", bindWorldParameters, settings);
    set.apply("lidar", bindScanParameters, caster_config);
    set.checkAllUsed();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "lo_replay: %s\n", e.what());
    return 2;
  }
  const bool use_imu = config.use_imu;

  const world::World world = world::buildWorld(settings);
  const world::Trajectory& truth = world.trajectory;
  std::printf("# world: %s, %zu triangles, %zu points\n", world.description.c_str(), world.mesh.size(),
              world.points.size());
  caster_config.seed = settings.seed;
  caster_config.point_radius = world.point_radius;
  raycaster::RayCaster caster(world.mesh, world.points, caster_config);
  std::printf("# lidar: %s, %.0f points per second at %.0f Hz\n", caster_config.model.name.c_str(),
              caster_config.model.points_per_second, caster_config.model.frame_rate_hz);

  const double frame = caster.frameDuration();
  const double end = std::min(truth.endTime() - 0.2, start + duration);
  const frames::MotorAngleTrack motor = tools::constantSpeedMotor(motor_speed, 0.0, end + 1.0);

  raycaster::ImuSimulatorConfig imu_config;
  imu_config.seed = settings.seed;
  raycaster::ImuSimulator imu(imu_config);
  const raycaster::ImuMotion imu_motion{[&truth](double t) { return truth.poseAt(t); },
                                        [motor_speed](double t) { return motor_speed * t; },
                                        [motor_speed](double) { return motor_speed; }};
  std::uint64_t next_imu = imu.firstIndexAtOrAfter(std::max(0.0, start - 0.5) + raycaster::kImuStencilHalfWidth);
  tools::ReplaySettings replay;
  replay.start = start;
  replay.end = end;
  replay.rotor_angle = [&motor](double t) { return *motor.thetaAt(t); };
  if (use_imu) {
    replay.before_frame = [&](double frame_end, lo::MotorizedLidarOdometry& odometry) {
      for (; imu.sampleTime(next_imu) <= frame_end + 0.01; ++next_imu) {
        const raycaster::ImuSample sample = imu.sample(next_imu, imu_motion);
        odometry.addImu({sample.time, sample.angular_velocity, sample.linear_acceleration});
      }
    };
  }
  double worst_position = 0.0, worst_rotation = 0.0, worst_speed = 0.0, lost_at = -1.0;
  double squared_position_sum = 0.0, registration_seconds = 0.0;  // for the RMS error and the LO's time
  std::size_t frames = 0, degenerate_frames = 0;  // registered frames, and those with a degenerate pose direction
  std::size_t velocity_resets = 0, map_voxels = 0, map_bytes = 0;  // the last, and the map's largest
  std::vector<evaluator::TimedPose> estimates, truths;             // for the evaluator's runaway test
  Eigen::Isometry3d previous_estimate = Eigen::Isometry3d::Identity(), previous_truth = previous_estimate;
  std::printf(
      "#    t  rot_err  pos_err  w_est  w_true    pts  corr  min_eig  it  v_err  nd  weakest direction [rx ry rz x y "
      "z]  status\n");
  const char* debug_env = std::getenv("LO_REPLAY_DEBUG");  // read once, not per frame
  const double debug_from = debug_env ? tools::number("LO_REPLAY_DEBUG", debug_env) : INFINITY;
  tools::driveLo(caster, truth, config, motor, replay, [&](const tools::DrivenFrame& f) {
    const lo::OdometryResult& r = f.result;
    const Eigen::Isometry3d& T = f.truth;
    registration_seconds += f.registration_seconds;
    ++frames;
    map_voxels = std::max(map_voxels, f.odometry.localMap().size());
    map_bytes = std::max(map_bytes, f.odometry.localMap().memoryBytes());
    if (r.degeneracy.degenerate_directions > 0) ++degenerate_frames;
    const double rot_err = degrees(tools::rotationAngle(T.linear().transpose() * r.T_WB.linear()));
    const double pos_err = (T.translation() - r.T_WB.translation()).norm();
    const double w_est =
        degrees(Eigen::AngleAxisd(previous_estimate.linear().transpose() * r.T_WB.linear()).angle()) / frame;
    const double w_true = degrees(Eigen::AngleAxisd(previous_truth.linear().transpose() * T.linear()).angle()) / frame;
    previous_estimate = r.T_WB;
    previous_truth = T;
    estimates.push_back({r.time, r.T_WB});
    truths.push_back({r.time, T});
    velocity_resets = r.velocity_resets;
    worst_position = std::max(worst_position, pos_err);
    squared_position_sum += pos_err * pos_err;
    worst_rotation = std::max(worst_rotation, rot_err);
    if (lost_at < 0 && (rot_err > 5.0 || pos_err > 2.0)) lost_at = r.time;
    const Eigen::Vector3d v_true = (T.translation() - truth.poseAt(r.time - 0.01).translation()) / 0.01;
    const double v_err = (r.linear_velocity_W - v_true).norm();
    worst_speed = std::max(worst_speed, v_err);
    if (r.time >= debug_from) {
      const auto& e = r.degeneracy.eigenvalues;
      std::printf("   v_est %.3f %.3f %.3f v_true %.3f %.3f %.3f std(v) %.3f %.3f\n", r.linear_velocity_W.x(),
                  r.linear_velocity_W.y(), r.linear_velocity_W.z(), v_true.x(), v_true.y(), v_true.z(),
                  std::sqrt(r.covariance(6, 6)), std::sqrt(r.covariance(7, 7)));
      std::printf("   eig [%.1f %.1f %.1f %.1f %.1f %.1f] w_est %.4f %.4f %.4f std(wz) %.4f std(yaw) %.4f deg\n", e(0),
                  e(1), e(2), e(3), e(4), e(5), r.angular_velocity_B.x(), r.angular_velocity_B.y(),
                  r.angular_velocity_B.z(), std::sqrt(r.covariance(11, 11)), degrees(std::sqrt(r.covariance(2, 2))));
    }
    if (f.index % static_cast<std::uint64_t>(every) == 0 || rot_err > 1.0) {
      const auto weakest = r.degeneracy.eigenvectors.col(0);
      std::printf(
          "%6.2f %7.2f %8.3f %6.1f %6.1f %6zu %5zu %8.1f %3d %6.2f %3d  [%5.2f %5.2f %5.2f %5.2f %5.2f %5.2f]  %s\n",
          r.time, rot_err, pos_err, w_est, w_true, r.points_used, r.correspondences, r.min_information_eigenvalue,
          r.iterations, v_err, r.degenerate_state_directions, weakest(0), weakest(1), weakest(2), weakest(3),
          weakest(4), weakest(5), lo::toString(r.status));
    }
  });
  const evaluator::SpeedErrorReport runaway = evaluator::speedError(estimates, truths);
  std::printf(
      "summary: %s %.0f-%.0f s: worst rotation %.2f deg, worst position %.3f m, worst speed error %.2f m/s, lost at "
      "%s, runaway at %s (the evaluator's test: speed over 1 s off by more than 1 m/s; worst %.2f m/s), velocity "
      "resets %zu, degenerate frames %zu of %zu, RMS position %.3f m, LO %.2f ms per frame, map at most %zu voxels "
      "(%.1f MB)\n",
      source.c_str(), start, end, worst_rotation, worst_position, worst_speed,
      lost_at < 0 ? "never" : std::to_string(lost_at).c_str(),
      runaway.first_runaway_time ? std::to_string(*runaway.first_runaway_time).c_str() : "never", runaway.max,
      velocity_resets, degenerate_frames, frames,
      frames > 0 ? std::sqrt(squared_position_sum / static_cast<double>(frames)) : 0.0,
      frames > 0 ? 1e3 * registration_seconds / static_cast<double>(frames) : 0.0, map_voxels,
      static_cast<double>(map_bytes) / 1e6);
  return 0;
}
