// lo_replay: the simulated motorized LiDAR and the LO in one process, without DDS, to study the
// LO on a trajectory quickly (a development tool: the scenes run the real components over DDS).
//
//   lo_replay (TRAJECTORY.csv | corridor | multilevel | campus) [--start S] [--duration S]
//             [--motor RAD_PER_S] [--seed N] [--attitude from_file|yaw_only|identity] [--every N]
//             [--linear-noise Q] [--angular-noise Q] [--iterations N] [--scan-voxel M]
//             [--map-voxel M] [--door-spacing M] [--imu 0|1] [--degeneracy-aware 0|1]
//             [--frame-velocity-std-linear V] [--frame-velocity-std-angular W]
//             [--degeneracy-threshold N] [--degeneracy-length M] [--degeneracy-period S]
//             [--measurement-variance M2] [--map-mean-points N] [--profile rich|mixed|poor] [--open-fraction F]
//             [--lidar-range-noise M] [--lidar-angular-noise-deg DEG] [--plane-distance M]
//             [--plane-min-spread-ratio R]
//             [--path-speed M_PER_S] [--poor-rows N]
//
// Builds the world as map_provider does (world::buildWorld): for an MCD trajectory the world
// generated around it (attitude turned z-up, 0.5 s smoothing, smooth interpolation, as the MCD
// scenes, with --profile or --open-fraction as map_provider's density_profile and open_fraction);
// for a procedural world its generated path at 1.5 m/s. Spins the motor at a constant
// speed, casts Mid-360 frames at 10 Hz, registers them, and prints per frame the rotation and
// position error against ground truth, the estimated and true yaw rate, and the LO's figures
// (`pts`: points the LO kept after its downsampling; `v_err`: the velocity's error, m/s; `nd`:
// degenerate directions of the 12-dimensional state; the weakest pose direction, rotation scaled
// at 10 m); then a summary line. --imu 1 simulates the Mid-360's IMU (the raycaster's simulator)
// and runs the LO LiDAR-inertial. LO_REPLAY_DEBUG=T prints every eigenvalue, the velocities and
// their standard deviations from T s on.
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "simulated_lidar.hpp"
#include "tool_main.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/raycaster/imu_simulator.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/world_source.hpp"

using namespace uampc;

namespace {

double degrees(double rad) { return rad * 180.0 / M_PI; }

}  // namespace

void printUsage(std::FILE* out);
int replay(int argc, char** argv);

int main(int argc, char** argv) { return tools::runTool("lo_replay", replay, argc, argv); }

void printUsage(std::FILE* out) {
  std::fprintf(
      out,
      "usage: lo_replay (TRAJECTORY.csv | corridor | multilevel | campus) [--start S] [--duration S (30)] "
      "[--motor RAD_PER_S (3.6)] [--seed N] [--attitude MODE] [--every N] [--linear-noise Q] [--angular-noise Q] "
      "[--iterations N] [--scan-voxel M] [--map-voxel M] [--max-registration-points N] [--registration-weakest-points N] [--door-spacing M] [--imu 0|1] [--degeneracy-aware 0|1] "
      "[--frame-velocity-std-linear V] [--frame-velocity-std-angular W] [--degeneracy-threshold N] "
      "[--degeneracy-length M] [--degeneracy-period S] [--measurement-variance M2] [--map-mean-points N] [--profile rich|mixed|poor] "
      "[--open-fraction F] [--lidar-range-noise M] [--lidar-angular-noise-deg DEG] [--plane-distance M] [--plane-min-spread-ratio R] "
      "[--path-speed M_PER_S] [--poor-rows N]\n"
      "Replays the simulated motorized LiDAR at a constant motor speed into the LO, without DDS, and prints per\n"
      "frame the errors against ground truth, then a summary line (docs/dev/testing.md, \"Development tools\"). Unset LO options take\n"
      "the LO's defaults.\n");
}

int replay(int argc, char** argv) {
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    printUsage(stdout);
    return 0;
  }
  if (argc < 2 || argc % 2 != 0) {
    printUsage(stderr);
    return 2;
  }
  const std::string source = argv[1];
  world::WorldSettings settings = tools::worldSettingsFor(source);
  double start = 0.0, duration = 30.0, motor_speed = 3.6;
  int every = 1;
  bool use_imu = false;
  lo::OdometryConfig config;
  raycaster::RayCasterConfig caster_config;  // noise-free unless asked
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const char* value = argv[i + 1];
    if (flag == "--start")
      start = tools::nonNegative(flag, value);
    else if (flag == "--duration")
      duration = tools::nonNegative(flag, value);
    else if (flag == "--motor")
      motor_speed = tools::number(flag, value);
    else if (flag == "--seed")
      settings.seed = static_cast<std::uint64_t>(tools::nonNegative(flag, value));
    else if (flag == "--attitude")
      settings.attitude = value;
    else if (flag == "--door-spacing")
      settings.corridor_door_spacing = tools::nonNegative(flag, value);
    else if (flag == "--lidar-range-noise")
      caster_config.range_noise_stddev = tools::nonNegative(flag, value);
    else if (flag == "--lidar-angular-noise-deg")
      caster_config.angular_noise_stddev = tools::nonNegative(flag, value) * M_PI / 180.0;
    else if (flag == "--path-speed")
      settings.path_speed = tools::nonNegative(flag, value);
    else if (flag == "--poor-rows")
      settings.campus_poor_rows = tools::count(flag, value);
    else if (flag == "--plane-distance")
      config.plane_max_point_distance = tools::nonNegative(flag, value);
    else if (flag == "--plane-min-spread-ratio") {
      // A ratio of the narrower spread to the wider: above 1 would refuse every plane.
      config.plane_min_spread_ratio = tools::nonNegative(flag, value);
      if (config.plane_min_spread_ratio > 1.0) throw std::invalid_argument(flag + ": '" + value + "' must be at most 1");
    }
    else if (flag == "--profile")
      settings.density_profile = value;
    else if (flag == "--open-fraction")
      settings.open_fraction = tools::nonNegative(flag, value);
    else if (flag == "--every")
      every = tools::count(flag, value);
    else if (flag == "--linear-noise")
      config.linear_process_noise = tools::nonNegative(flag, value);
    else if (flag == "--angular-noise")
      config.angular_process_noise = tools::nonNegative(flag, value);
    else if (flag == "--iterations")
      config.max_iterations = tools::count(flag, value);
    else if (flag == "--scan-voxel")
      config.scan_voxel_size = tools::nonNegative(flag, value);
    else if (flag == "--map-voxel")
      config.map_voxel_size = tools::nonNegative(flag, value);
    else if (flag == "--max-registration-points")
      config.max_registration_points = tools::count(flag, value);
    else if (flag == "--registration-weakest-points")
      config.registration_weakest_points = tools::nonNegative(flag, value);
    else if (flag == "--imu")
      use_imu = tools::count(flag, value) != 0;
    else if (flag == "--degeneracy-threshold")
      config.degeneracy_threshold = tools::nonNegative(flag, value);
    else if (flag == "--degeneracy-length")
      config.degeneracy_scales.length = tools::nonNegative(flag, value);
    else if (flag == "--map-mean-points")
      config.map_mean_points = tools::count(flag, value);
    else if (flag == "--measurement-variance")
      config.measurement_variance = tools::nonNegative(flag, value);
    else if (flag == "--degeneracy-period")
      config.degeneracy_scales.period = tools::nonNegative(flag, value);
    else if (flag == "--degeneracy-aware")
      config.degeneracy_aware = tools::count(flag, value) != 0;
    else if (flag == "--frame-velocity-std-linear")
      config.frame_velocity_std_linear = tools::nonNegative(flag, value);
    else if (flag == "--frame-velocity-std-angular")
      config.frame_velocity_std_angular = tools::nonNegative(flag, value);
    else {
      std::fprintf(stderr, "lo_replay: unknown option %s\n", flag.c_str());
      return 2;
    }
  }

  const world::World world = world::buildWorld(settings);
  const world::Trajectory& truth = world.trajectory;
  std::printf("# world: %s, %zu triangles\n", world.description.c_str(), world.mesh.size());
  caster_config.seed = settings.seed;
  raycaster::RayCaster caster(world.mesh, caster_config);

  const double frame = caster.frameDuration();
  const double end = std::min(truth.endTime() - 0.2, start + duration);
  const frames::MotorAngleTrack motor = tools::constantSpeedMotor(motor_speed, 0.0, end + 1.0);

  config.use_imu = use_imu;
  raycaster::ImuSimulatorConfig imu_config;
  imu_config.seed = settings.seed;
  raycaster::ImuSimulator imu(imu_config);
  const raycaster::ImuMotion imu_motion{[&truth](double t) { return truth.poseAt(t); },
                                        [motor_speed](double t) { return motor_speed * t; },
                                        [motor_speed](double) { return motor_speed; }};
  std::uint64_t next_imu = imu.firstIndexAtOrAfter(std::max(0.0, start - 0.5) + raycaster::kImuStencilHalfWidth);
  lo::MotorizedLidarOdometry odometry;  // replaced once the first frame's end is known
  bool started = false;
  double worst_position = 0.0, worst_rotation = 0.0, worst_speed = 0.0, lost_at = -1.0;
  double squared_position_sum = 0.0, registration_seconds = 0.0;  // for the RMS error and the LO's time
  std::size_t frames = 0, degenerate_frames = 0;  // registered frames, and those with a degenerate pose direction
  Eigen::Isometry3d previous_estimate = Eigen::Isometry3d::Identity(), previous_truth = previous_estimate;
  std::printf(
      "#    t  rot_err  pos_err  w_est  w_true    pts  corr  min_eig  it  v_err  nd  weakest direction [rx ry rz x y "
      "z]  status\n");
  const char* debug_env = std::getenv("LO_REPLAY_DEBUG");  // read once, not per frame
  const double debug_from = debug_env ? tools::number("LO_REPLAY_DEBUG", debug_env) : INFINITY;
  std::uint64_t k = static_cast<std::uint64_t>(std::llround(start / frame));
  for (double t0 = k * frame; t0 + frame <= end; t0 = (++k) * frame) {
    const lo::Scan scan = tools::toOdometryScan(caster.castFrame(k, t0, truth, motor));
    if (!started) {
      tools::startAtTruth(config, truth, tools::scanEndTime(scan));
      odometry = lo::MotorizedLidarOdometry(config);
      started = true;
    }
    for (; use_imu && imu.sampleTime(next_imu) <= t0 + frame + 0.01; ++next_imu) {
      const raycaster::ImuSample sample = imu.sample(next_imu, imu_motion);
      odometry.addImu({sample.time, sample.angular_velocity, sample.linear_acceleration});
    }
    const auto registration_start = std::chrono::steady_clock::now();
    const lo::OdometryResult r = odometry.registerScan(scan, motor);
    registration_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - registration_start).count();
    ++frames;
    if (r.degeneracy.degenerate_directions > 0) ++degenerate_frames;
    const Eigen::Isometry3d T = truth.poseAt(r.time);
    const double rot_err = degrees(tools::rotationAngle(T.linear().transpose() * r.T_WB.linear()));
    const double pos_err = (T.translation() - r.T_WB.translation()).norm();
    const double w_est =
        degrees(Eigen::AngleAxisd(previous_estimate.linear().transpose() * r.T_WB.linear()).angle()) / frame;
    const double w_true = degrees(Eigen::AngleAxisd(previous_truth.linear().transpose() * T.linear()).angle()) / frame;
    previous_estimate = r.T_WB;
    previous_truth = T;
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
    if (k % static_cast<std::uint64_t>(every) == 0 || rot_err > 1.0) {
      const auto weakest = r.degeneracy.eigenvectors.col(0);
      std::printf(
          "%6.2f %7.2f %8.3f %6.1f %6.1f %6zu %5zu %8.1f %3d %6.2f %3d  [%5.2f %5.2f %5.2f %5.2f %5.2f %5.2f]  %s\n",
          r.time, rot_err, pos_err, w_est, w_true, r.points_used, r.correspondences, r.min_information_eigenvalue,
          r.iterations, v_err, r.degenerate_state_directions, weakest(0), weakest(1), weakest(2), weakest(3),
          weakest(4), weakest(5), lo::toString(r.status));
    }
  }
  std::printf(
      "summary: %s %.0f-%.0f s: worst rotation %.2f deg, worst position %.3f m, worst speed error %.2f m/s, lost at "
      "%s, degenerate frames %zu of %zu, RMS position %.3f m, LO %.2f ms per frame\n",
      source.c_str(), start, end, worst_rotation, worst_position, worst_speed,
      lost_at < 0 ? "never" : std::to_string(lost_at).c_str(), degenerate_frames, frames,
      frames > 0 ? std::sqrt(squared_position_sum / static_cast<double>(frames)) : 0.0,
      frames > 0 ? 1e3 * registration_seconds / static_cast<double>(frames) : 0.0);
  return 0;
}
