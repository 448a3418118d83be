// The simulator chain over DDS (map_provider, motor_bridge, raycaster in another process): frames
// arrive at 10 Hz, and every point, de-rotated with the recorded encoder angles and ground truth
// (Eq. 1), lands on the corridor's planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/run_files/csv.hpp"
#include "uampc/world/trajectory.hpp"

namespace uampc::test {
namespace {

double distanceToCorridor(const Eigen::Vector3d& p) {
  return std::min({std::abs(std::abs(p.y()) - 1.5), std::abs(p.z()), std::abs(p.z() - 3.0), std::abs(p.x()),
                   std::abs(p.x() - 300.0)});
}

// A run's recorded scans, encoder states and ground truth (the csv_recorder's files).
struct RecordedRun {
  world::Trajectory ground_truth;
  std::vector<frames::MotorReading> encoder;
  run_files::CsvTable scans;  // stamp, x, y, z, intensity, t, ...
};

RecordedRun readRun(const std::string& out) {
  std::vector<world::TimedPose> poses;
  for (const auto& row : run_files::readCsv(out + "/recorder_ground_truth.csv").rows) {
    poses.push_back({row[0], {row[1], row[2], row[3]}, Eigen::Quaterniond(row[7], row[4], row[5], row[6])});
  }
  RecordedRun run{world::Trajectory(poses), {}, run_files::readCsv(out + "/recorder_scans.csv")};
  for (const auto& row : run_files::readCsv(out + "/recorder_motor_states.csv").rows)
    run.encoder.push_back({row[0], row[1], row[2]});
  return run;
}

// Every point de-rotated with `calibration` (its encoder zero and clock offset taken out of the
// recorded encoder states, Eq. 1): the distance of each to the corridor's planes.
std::vector<double> distancesToCorridor(const RecordedRun& run, const frames::MotorLidarCalibration& calibration) {
  frames::MotorAngleTrack motor(1000.0);
  for (const auto& reading : run.encoder) motor.add(frames::rotorReading(reading, calibration));
  std::vector<double> distances;
  for (const auto& row : run.scans.rows) {
    const double t = row[0] + row[5];
    const auto theta = motor.thetaAt(t);
    if (!theta) continue;  // a clock offset moves the encoder's span off the first points
    const Eigen::Vector3d p_W =
        frames::lidarToWorld({row[1], row[2], row[3]}, *theta, calibration, run.ground_truth.poseAt(t));
    distances.push_back(distanceToCorridor(p_W));
  }
  return distances;
}

TEST(Simulator, ScansDeRotatedWithRecordedStatesLandOnTheSurfaces) {
  const std::string out = freshDirectory("simulator_corridor");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/corridor_sim.yaml") + " --out " + out +
                                   domainOverride(DomainBlock::kSimulator, 0));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const RecordedRun run = readRun(out);
  std::map<double, int> points_per_frame;
  for (const auto& row : run.scans.rows) {
    ++points_per_frame[row[0]];
    ASSERT_GE(row[5], 0.0);
    ASSERT_LT(row[5], 0.1);
    const Eigen::Vector3d p_L(row[1], row[2], row[3]);
    ASSERT_GE(p_L.norm(), 1.5 - 1e-4);  // Mid-360 range limits
    ASSERT_LE(p_L.norm(), 40.0 + 1e-4);
  }
  const std::vector<double> distances = distancesToCorridor(run, frames::MotorLidarCalibration::referenceRig());
  ASSERT_EQ(distances.size(), run.scans.rows.size()) << "points without an encoder state around them";
  // The frames of [0, 0.5) s, at their start times; each with a plausible number of returns.
  ASSERT_EQ(points_per_frame.size(), 5u);
  int k = 0;
  for (const auto& [stamp, count] : points_per_frame) {
    EXPECT_NEAR(stamp, 0.1 * k++, 1e-9);
    EXPECT_GT(count, 5000);
    EXPECT_LE(count, 20000);
  }
  const double worst = *std::max_element(distances.begin(), distances.end());
  EXPECT_LT(worst, 1e-3) << "a de-rotated point is " << worst << " m off the corridor's planes";
}

// A simulated rig off the believed one (the raycaster's mounting_error_*): de-rotated with the
// rig the scene describes, the points miss the corridor's planes; with the true rig (the believed
// one composed with the error), they land on them.
TEST(Simulator, AMountingErrorPutsPointsOffThePlanesUnlessTheTrueRigDeRotatesThem) {
  const std::string out = freshDirectory("simulator_mounting_error");
  const CommandResult r = runUampc(
      "launch " + sourcePath("tests/scenes/corridor_sim.yaml") + " --out " + out +
      domainOverride(DomainBlock::kSimulator, 3) +
      " --set 'lidar.mounting_error_rpy_deg=[1.0, -0.5, 2.0]' --set 'lidar.mounting_error_offset=[0.02, -0.01, 0.03]'"
      " --set lidar.mounting_error_encoder_deg=1.5 --set lidar.mounting_error_time_offset=0.004");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const RecordedRun run = readRun(out);
  const auto believed = frames::MotorLidarCalibration::referenceRig();
  frames::MountingError error;
  error.rotation_rpy = Eigen::Vector3d(1.0, -0.5, 2.0) * M_PI / 180.0;
  error.offset = {0.02, -0.01, 0.03};
  error.encoder_offset = 1.5 * M_PI / 180.0;
  error.time_offset = 0.004;
  const auto truth = frames::withMountingError(believed, error);

  const std::vector<double> with_truth = distancesToCorridor(run, truth);
  ASSERT_GT(with_truth.size(), 0.95 * run.scans.rows.size());
  EXPECT_LT(*std::max_element(with_truth.begin(), with_truth.end()), 1e-3);
  const std::vector<double> with_belief = distancesToCorridor(run, believed);
  ASSERT_GT(with_belief.size(), 0.95 * run.scans.rows.size());
  const auto off = std::count_if(with_belief.begin(), with_belief.end(), [](double d) { return d > 0.01; });
  EXPECT_GT(off, static_cast<long>(with_belief.size() / 2)) << off << " of " << with_belief.size() << " points off";
  // Each part of the error alone moves the points too: none is dropped on the way to the caster.
  for (int part = 0; part < 4; ++part) {
    frames::MountingError one;
    if (part == 0) one.rotation_rpy = error.rotation_rpy;
    if (part == 1) one.offset = error.offset;
    if (part == 2) one.encoder_offset = error.encoder_offset;
    if (part == 3) one.time_offset = error.time_offset;
    frames::MountingError rest = error;
    rest.rotation_rpy -= one.rotation_rpy;
    rest.offset -= one.offset;
    rest.encoder_offset -= one.encoder_offset;
    rest.time_offset -= one.time_offset;
    const std::vector<double> d = distancesToCorridor(run, frames::withMountingError(believed, rest));
    EXPECT_GT(*std::max_element(d.begin(), d.end()), 5e-3) << "part " << part << " of the error is not cast";
  }
}

// The raycaster's IMU on a straight path at constant speed, the motor at 3.6 rad/s: every sample
// once, in order, on the 200 Hz grid; the gyro sees the motor's spin about the base z axis (in L,
// tilted 30 degrees) and the accelerometer gravity, both within the default noise.
TEST(Simulator, ImuSamplesComeInOrderAndSeeTheMotorAndGravity) {
  const std::string out = freshDirectory("simulator_imu");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/corridor_sim.yaml") + " --out " + out +
                                   domainOverride(DomainBlock::kSimulator, 2) + " --set lidar.imu=true");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = run_files::readCsv(out + "/recorder_imu.csv").rows;
  ASSERT_GT(rows.size(), 120u);  // 0.7 s at 200 Hz, less the start and the last steps
  const double tilt = 30.0 * M_PI / 180.0;
  const Eigen::Vector3d motor_axis_L(0.0, std::sin(tilt), std::cos(tilt));  // R_ML^T e_z
  const double gyro_sigma = 4.5e-3 * M_PI / 180.0 * std::sqrt(200.0), accel_sigma = 100e-6 * 9.80665 * std::sqrt(200.0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double t = rows[i][0];
    if (i > 0) {
      ASSERT_NEAR(t - rows[i - 1][0], 0.005, 1e-8) << "at t=" << t;
    }
    ASSERT_NEAR(t, 0.005 * std::round(t / 0.005), 1e-8);
    if (t < 0.05) continue;  // the motor starts at the first command
    const Eigen::Vector3d gyro(rows[i][1], rows[i][2], rows[i][3]), accel(rows[i][4], rows[i][5], rows[i][6]);
    EXPECT_LT((gyro - 3.6 * motor_axis_L).cwiseAbs().maxCoeff(), 6.0 * gyro_sigma) << "at t=" << t;
    EXPECT_LT((accel - 9.81 * motor_axis_L).cwiseAbs().maxCoeff(), 6.0 * accel_sigma) << "at t=" << t;
  }
}

TEST(Simulator, CorruptMapsAndTrajectoriesStopTheRunNamingTheFile) {
  const std::string dir = freshDirectory("simulator_bad_inputs");
  const std::string good_tum = dir + "/path.tum";
  std::ofstream(good_tum) << "0 0 0 1 0 0 0 1\n1 1 0 1 0 0 0 1\n2 2 0 1 0 0 0 1\n";
  const std::string corrupt_pcd = dir + "/corrupt.pcd";
  std::ofstream(corrupt_pcd) << "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                "WIDTH 100\nHEIGHT 1\nPOINTS 100\nDATA ascii\n1 2 3\n";
  const std::string bad_tum = dir + "/bad.tum";
  std::ofstream(bad_tum) << "0 0 0 1 0 0 0 1\n1 1 0 1 0 0\n";
  const std::string scene = sourcePath("tests/scenes/bad_map.yaml");
  CommandResult r = runUampc("launch " + scene + domainOverride(DomainBlock::kSimulator, 1) +
                             " --set world.map_file=" + corrupt_pcd + " --set world.trajectory_file=" + good_tum);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("component 'world' (map_provider) could not start: " + corrupt_pcd), std::string::npos)
      << r.output;
  r = runUampc("launch " + scene + domainOverride(DomainBlock::kSimulator, 1) +
               " --set world.world=campus --set world.trajectory_file=" + bad_tum);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(bad_tum + ":2:"), std::string::npos) << r.output;
}

// A pose 1e20 m out aborted the ray-caster inside Embree (signal 6). It is refused when the
// trajectory is read, and the run does not start (docs/user/faults.md).
TEST(Simulator, ATrajectoryFarFromTheOriginIsRefusedBeforeTheRayCasterRuns) {
  const std::string dir = freshDirectory("simulator_far_trajectory");
  const std::string far_tum = dir + "/far.tum";
  std::ofstream(far_tum) << "0 0 0 1 0 0 0 1\n1 1e20 0 1 0 0 0 1\n2 2 0 1 0 0 0 1\n";
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/corridor_sim.yaml") +
                                   domainOverride(DomainBlock::kSimulator, 3) +
                                   " --set world.trajectory=file --set world.trajectory_file=" + far_tum);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("component 'world' (map_provider) could not start: " + far_tum +
                          ":2: position is 1e+20 m from the origin"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("signal"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace uampc::test
