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
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
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

// What the command line asks for; the components' parameters with --set already applied.
struct ReplayArguments {
  std::string source;
  double start = 0.0, duration = 30.0, motor_speed = 3.6;
  std::uint64_t seed = 1;
  int every = 1;
  world::WorldSettings world;
  lo::OdometryConfig odometry;
  raycaster::RayCasterConfig caster;  // exact casts unless --set lidar.range_noise=M (scenes: 0.02)
};

// Parses argv into arguments; an exit code when the run must not go on (--help, or bad input,
// said on stderr).
std::optional<int> parseArguments(int argc, char** argv, ReplayArguments& arguments) {
  CLI::App app{
      "Replays the simulated motorized LiDAR at a constant motor speed into the LO, without DDS, and prints per\n"
      "frame the errors against ground truth, then a summary line (docs/dev/testing.md, \"Development tools\").",
      "lo_replay"};
  ReplayArguments& a = arguments;
  std::string lidar_name = "livox_mid360";
  std::vector<std::string> assignments;
  app.add_option("SOURCE", a.source, "an MCD trajectory (.csv), or corridor, multilevel or campus")->required();
  app.add_option("--start", a.start, "s of the trajectory skipped")
      ->check(command_line::kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--duration", a.duration, "s replayed")
      ->check(command_line::kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--motor", a.motor_speed, "constant motor speed, rad/s")
      ->check(command_line::kFinite)
      ->capture_default_str();
  app.add_option("--lidar", lidar_name, "the LiDAR model on the motor, as a scene's rig.lidar_model")
      ->check(CLI::IsMember(lidar::namedLidarModels()))
      ->capture_default_str();
  app.add_option("--seed", a.seed, "the world's and the noise's seed")->capture_default_str();
  app.add_option("--every", a.every, "print every N-th frame (and every frame more than 1 degree off)")
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
  a.world = tools::worldSettingsFor(a.source);
  a.world.seed = a.seed;
  a.caster.model = lidar::lidarModelByName(lidar_name);
  try {
    tools::ParameterOverrides set(assignments);
    set.apply("lo", bindLoParameters, a.odometry);
    set.apply("world", bindWorldParameters, a.world);
    set.apply("lidar", bindScanParameters, a.caster);
    set.checkAllUsed();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "lo_replay: %s\n", e.what());
    return 2;
  }
  return std::nullopt;
}

// The LO's figures of one frame, against the truth, as a frame line prints them.
struct FrameErrors {
  double rotation = 0.0;        // deg
  double position = 0.0;        // m
  double rate_estimated = 0.0;  // deg/s, over the frame
  double rate_true = 0.0;       // deg/s
  double velocity = 0.0;        // m/s
  Eigen::Vector3d v_true = Eigen::Vector3d::Zero();
};

void printFrameHeader() {
  std::printf(
      "#    t  rot_err  pos_err  w_est  w_true    pts  corr  min_eig  it  v_err  nd  weakest direction [rx ry rz x y "
      "z]  status\n");
}

void printFrame(const lo::OdometryResult& r, const FrameErrors& e) {
  const auto weakest = r.degeneracy.eigenvectors.col(0);
  std::printf(
      "%6.2f %7.2f %8.3f %6.1f %6.1f %6zu %5zu %8.1f %3d %6.2f %3d  [%5.2f %5.2f %5.2f %5.2f %5.2f %5.2f]  %s\n",
      r.time, e.rotation, e.position, e.rate_estimated, e.rate_true, r.points_used, r.correspondences,
      r.min_information_eigenvalue, r.iterations, e.velocity, r.degenerate_state_directions, weakest(0), weakest(1),
      weakest(2), weakest(3), weakest(4), weakest(5), lo::toString(r.status));
}

// LO_REPLAY_DEBUG's lines: the velocities, every eigenvalue and the standard deviations.
void printDebug(const lo::OdometryResult& r, const FrameErrors& e) {
  const auto& ev = r.degeneracy.eigenvalues;
  std::printf("   v_est %.3f %.3f %.3f v_true %.3f %.3f %.3f std(v) %.3f %.3f\n", r.linear_velocity_W.x(),
              r.linear_velocity_W.y(), r.linear_velocity_W.z(), e.v_true.x(), e.v_true.y(), e.v_true.z(),
              std::sqrt(r.covariance(6, 6)), std::sqrt(r.covariance(7, 7)));
  std::printf("   eig [%.1f %.1f %.1f %.1f %.1f %.1f] w_est %.4f %.4f %.4f std(wz) %.4f std(yaw) %.4f deg\n", ev(0),
              ev(1), ev(2), ev(3), ev(4), ev(5), r.angular_velocity_B.x(), r.angular_velocity_B.y(),
              r.angular_velocity_B.z(), std::sqrt(r.covariance(11, 11)), degrees(std::sqrt(r.covariance(2, 2))));
}

// The whole run's figures, frame by frame, for the summary line.
class RunSummary {
 public:
  RunSummary(const world::Trajectory& truth, double frame) : truth_(truth), frame_(frame) {}

  // The frame's errors against the truth, counted into the run's.
  FrameErrors add(const tools::DrivenFrame& f) {
    const lo::OdometryResult& r = f.result;
    const Eigen::Isometry3d& T = f.truth;
    registration_seconds_ += f.registration_seconds;
    ++frames_;
    map_voxels_ = std::max(map_voxels_, f.odometry.localMap().size());
    map_bytes_ = std::max(map_bytes_, f.odometry.localMap().memoryBytes());
    if (r.degeneracy.degenerate_directions > 0) ++degenerate_frames_;
    FrameErrors e;
    e.rotation = degrees(tools::rotationAngle(T.linear().transpose() * r.T_WB.linear()));
    e.position = (T.translation() - r.T_WB.translation()).norm();
    e.rate_estimated =
        degrees(Eigen::AngleAxisd(previous_estimate_.linear().transpose() * r.T_WB.linear()).angle()) / frame_;
    e.rate_true = degrees(Eigen::AngleAxisd(previous_truth_.linear().transpose() * T.linear()).angle()) / frame_;
    previous_estimate_ = r.T_WB;
    previous_truth_ = T;
    estimates_.push_back({r.time, r.T_WB});
    truths_.push_back({r.time, T});
    velocity_resets_ = r.velocity_resets;
    worst_position_ = std::max(worst_position_, e.position);
    squared_position_sum_ += e.position * e.position;
    worst_rotation_ = std::max(worst_rotation_, e.rotation);
    if (lost_at_ < 0 && (e.rotation > 5.0 || e.position > 2.0)) lost_at_ = r.time;
    e.v_true = (T.translation() - truth_.poseAt(r.time - 0.01).translation()) / 0.01;
    e.velocity = (r.linear_velocity_W - e.v_true).norm();
    worst_speed_ = std::max(worst_speed_, e.velocity);
    return e;
  }

  void print(const std::string& source, double start, double end) const {
    const evaluator::SpeedErrorReport runaway = evaluator::speedError(estimates_, truths_);
    const double frames = static_cast<double>(frames_);
    std::printf(
        "summary: %s %.0f-%.0f s: worst rotation %.2f deg, worst position %.3f m, worst speed error %.2f m/s, lost "
        "at %s, runaway at %s (the evaluator's test: speed over 1 s off by more than 1 m/s; worst %.2f m/s), "
        "velocity resets %zu, degenerate frames %zu of %zu, RMS position %.3f m, LO %.2f ms per frame, map at most "
        "%zu voxels (%.1f MB)\n",
        source.c_str(), start, end, worst_rotation_, worst_position_, worst_speed_,
        lost_at_ < 0 ? "never" : std::to_string(lost_at_).c_str(),
        runaway.first_runaway_time ? std::to_string(*runaway.first_runaway_time).c_str() : "never", runaway.max,
        velocity_resets_, degenerate_frames_, frames_, frames_ > 0 ? std::sqrt(squared_position_sum_ / frames) : 0.0,
        frames_ > 0 ? 1e3 * registration_seconds_ / frames : 0.0, map_voxels_, static_cast<double>(map_bytes_) / 1e6);
  }

 private:
  const world::Trajectory& truth_;
  double frame_;  // s
  double worst_position_ = 0.0, worst_rotation_ = 0.0, worst_speed_ = 0.0, lost_at_ = -1.0;
  double squared_position_sum_ = 0.0, registration_seconds_ = 0.0;  // for the RMS error and the LO's time
  std::size_t frames_ = 0, degenerate_frames_ = 0;  // registered frames, and those with a degenerate pose direction
  std::size_t velocity_resets_ = 0, map_voxels_ = 0, map_bytes_ = 0;  // the last, and the map's largest
  std::vector<evaluator::TimedPose> estimates_, truths_;              // for the evaluator's runaway test
  Eigen::Isometry3d previous_estimate_ = Eigen::Isometry3d::Identity(), previous_truth_ = previous_estimate_;
};

// With lo.use_imu: the simulated IMU's readings up to each frame's end, handed to the LO before
// the frame (ReplaySettings::before_frame).
class ImuFeed {
 public:
  ImuFeed(const ReplayArguments& a, const world::Trajectory& truth)
      : imu_(configFor(a)),
        motion_{[&truth](double t) { return truth.poseAt(t); }, [speed = a.motor_speed](double t) { return speed * t; },
                [speed = a.motor_speed](double) { return speed; }},
        next_(imu_.firstIndexAtOrAfter(std::max(0.0, a.start - 0.5) + raycaster::kImuStencilHalfWidth)) {}

  void operator()(double frame_end, lo::MotorizedLidarOdometry& odometry) {
    for (; imu_.sampleTime(next_) <= frame_end + 0.01; ++next_) {
      const raycaster::ImuSample sample = imu_.sample(next_, motion_);
      odometry.addImu({sample.time, sample.angular_velocity, sample.linear_acceleration});
    }
  }

 private:
  static raycaster::ImuSimulatorConfig configFor(const ReplayArguments& a) {
    raycaster::ImuSimulatorConfig config;
    config.seed = a.world.seed;
    return config;
  }
  raycaster::ImuSimulator imu_;
  raycaster::ImuMotion motion_;
  std::uint64_t next_;  // the next sample's index
};

}  // namespace

int replay(int argc, char** argv);

int main(int argc, char** argv) { return tools::runTool("lo_replay", replay, argc, argv); }

int replay(int argc, char** argv) {
  ReplayArguments a;
  if (const std::optional<int> exit_code = parseArguments(argc, argv, a)) return *exit_code;

  const world::World world = world::buildWorld(a.world);
  const world::Trajectory& truth = world.trajectory;
  std::printf("# world: %s, %zu triangles, %zu points\n", world.description.c_str(), world.mesh.size(),
              world.points.size());
  a.caster.seed = a.world.seed;
  a.caster.point_radius = world.point_radius;
  raycaster::RayCaster caster(world.mesh, world.points, a.caster);
  std::printf("# lidar: %s, %.0f points per second at %.0f Hz\n", a.caster.model.name.c_str(),
              a.caster.model.points_per_second, a.caster.model.frame_rate_hz);

  const double end = std::min(truth.endTime() - 0.2, a.start + a.duration);
  const frames::MotorAngleTrack motor = tools::constantSpeedMotor(a.motor_speed, 0.0, end + 1.0);
  tools::ReplaySettings replay;
  replay.start = a.start;
  replay.end = end;
  replay.rotor_angle = [&motor](double t) { return *motor.thetaAt(t); };
  std::optional<ImuFeed> imu;
  if (a.odometry.use_imu) {
    imu.emplace(a, truth);
    replay.before_frame = [&imu](double frame_end, lo::MotorizedLidarOdometry& odometry) {
      (*imu)(frame_end, odometry);
    };
  }

  RunSummary summary(truth, caster.frameDuration());
  printFrameHeader();
  const char* debug_env = std::getenv("LO_REPLAY_DEBUG");  // read once, not per frame
  const double debug_from = debug_env ? tools::number("LO_REPLAY_DEBUG", debug_env) : INFINITY;
  const auto every = static_cast<std::uint64_t>(a.every);
  tools::driveLo(caster, truth, a.odometry, motor, replay, [&](const tools::DrivenFrame& f) {
    const FrameErrors e = summary.add(f);
    if (f.result.time >= debug_from) printDebug(f.result, e);
    if (f.index % every == 0 || e.rotation > 1.0) printFrame(f.result, e);
  });
  summary.print(a.source, a.start, end);
  return 0;
}
