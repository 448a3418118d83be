// LO accuracy over DDS: on a feature-rich campus at a constant 3.6 rad/s the drift stays under 1%
// of the distance over 300 m; through the poor row the LiDAR-inertial LO holds and says where the
// geometry degenerates; a point-map scene's held start keeps the estimate where the rig stands.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <sstream>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/time_series.hpp"

namespace uampc::test {
namespace {

std::vector<std::vector<double>> readTum(const std::string& path) {
  std::vector<std::vector<double>> rows;
  std::stringstream in(readFile(path));
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream fields(line);
    std::vector<double> row;
    for (double v; fields >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

// A run of campus_ua_mpc.yaml with the given --set options (and --out DIR); its estimated and true
// trajectories, pose by pose (the evaluator writes them paired).
struct PairedRun {
  std::vector<std::vector<double>> estimate, truth;
};
PairedRun runCampus(const std::string& out, const std::string& options) {
  const CommandResult r =
      runUampc("launch " + sourcePath("config/scenes/campus_ua_mpc.yaml") + " --out " + out + " " + options);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  PairedRun run{readTum(out + "/estimate.tum"), readTum(out + "/ground_truth.tum")};
  EXPECT_EQ(run.estimate.size(), run.truth.size());
  if (run.estimate.size() != run.truth.size()) run = PairedRun{};  // the caller sees no poses
  return run;
}

double positionError(const PairedRun& run, std::size_t i) {
  const auto& e = run.estimate[i];
  const auto& t = run.truth[i];
  return std::hypot(e[1] - t[1], e[2] - t[2], e[3] - t[3]);
}

TEST(LoDrift, UnderOnePercentOfDistanceOver300MetresOnARichCampusAtConstantSpeed) {
  const std::string out = freshDirectory("lo_drift");
  // 3 m/s for 105 s: 300 m along the campus streets, every block rich in geometry (the poor
  // blocks are where UA-MPC matters; constant speed is known to struggle there).
  const PairedRun run = runCampus(out, domainOverride(DomainBlock::kLoDrift, 0) +
                                           " --set clock.duration=105 --set world.path_speed=3.0 "
                                           "--set world.campus_poor_rows=0 --set controller.mode=constant "
                                           "--set controller.constant_speed=3.6");
  const auto& truth = run.truth;
  ASSERT_GT(truth.size(), 1000u);
  double distance = 0, worst_ratio = 0;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    distance += std::hypot(truth[i][1] - truth[i - 1][1], truth[i][2] - truth[i - 1][2], truth[i][3] - truth[i - 1][3]);
    if (distance > 50.0) worst_ratio = std::max(worst_ratio, positionError(run, i) / distance);
  }
  EXPECT_GE(distance, 300.0);
  EXPECT_LT(worst_ratio, 0.01) << "drift reached " << 100 * worst_ratio << "% of the distance travelled";
  std::cout << "LO drift: worst " << 100 * worst_ratio << "% of distance over " << distance << " m\n";
}

// Through the campus's row of poor blocks (plain walls, a lawn) at 3 m/s, where the LiDAR-only LO
// ran away (docs/results/lo-degenerate-geometry.md): in LiDAR-inertial mode it holds, never says
// it is lost, and reports the degenerate directions it crosses on /lo/metrics.
TEST(LoDrift, LidarInertialHoldsThroughThePoorRowAndReportsItDegenerate) {
  const std::string out = freshDirectory("lo_poor_row");
  const PairedRun run = runCampus(out, domainOverride(DomainBlock::kLoDrift, 1) +
                                           " --set clock.duration=70 --set world.path_speed=3.0 "
                                           "--set lidar.imu=true --set lo.use_imu=true --set controller.mode=constant "
                                           "--set controller.constant_speed=3.6");
  ASSERT_GT(run.truth.size(), 600u);
  double worst = 0.0;
  for (std::size_t i = 0; i < run.truth.size(); ++i) worst = std::max(worst, positionError(run, i));
  EXPECT_LT(worst, 0.5);
  const std::string metrics = readFile(out + "/metrics.json");
  EXPECT_NE(metrics.find("\"lost_frames\": 0"), std::string::npos) << metrics;
  EXPECT_EQ(metrics.find("first_lost_time"), std::string::npos) << metrics;
  // timings.csv holds /lo/metrics: the poor row must show up as degenerate directions.
  std::size_t degenerate_frames = 0;
  for (const run_files::TimingRow& row : run_files::readTimings(out + "/" + run_files::kTimingsFile)) {
    if (row.source == "lo" && row.name == "degenerate_directions" && row.value > 0) ++degenerate_frames;
  }
  EXPECT_GT(degenerate_frames, 10u);
  // metrics.json counts the same frames (the evaluator, from /lo/metrics).
  const auto summary = run_files::readMetricsFile(out + "/metrics.json");
  ASSERT_TRUE(summary);
  EXPECT_EQ(summary->lo.degenerate_frames, static_cast<std::int64_t>(degenerate_frames));
  EXPECT_GE(summary->lo.frames, 690);  // 70 s of 10 Hz frames
  std::cout << "poor row with the IMU: worst position error " << worst << " m, " << degenerate_frames
            << " frames with degenerate directions\n";
}

// A point-map scene's held start (start_hold 2 s, the LO's first map over 1.8 s at rest,
// docs/decisions/lo-initial-map.md): on TUHH's mesh, seed 3, the LO's first registration against
// one frame slid 0.2 m and gave the standing rig 2.8 m/s, which the acceleration check then kept
// for a second. With the initial map the estimate stands still while the rig does.
TEST(LoDrift, TheHeldStartOfAPointMapSceneStaysWhereTheRigStands) {
  const std::string out = freshDirectory("lo_held_start");
  const CommandResult r = runUampc(
      "launch " + sourcePath("config/scenes/mcd_tuhh_pointmap.yaml") + " --out " + out +
      domainOverride(DomainBlock::kLoDrift, 2) +
      " --set seed=3 --set world.point_map_resolution=0 --set rig.lidar_model=livox_mid360 --set clock.duration=4"
      " --set controller.mode=constant --set controller.constant_speed=3.6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const PairedRun run{readTum(out + "/estimate.tum"), readTum(out + "/ground_truth.tum")};
  ASSERT_EQ(run.estimate.size(), run.truth.size());
  ASSERT_GT(run.estimate.size(), 30u);
  double worst = 0.0;
  for (std::size_t i = 0; i < run.estimate.size(); ++i) {
    if (run.truth[i][0] < 2.0) worst = std::max(worst, positionError(run, i));
  }
  EXPECT_LT(worst, 0.1) << "the estimate moved while the rig stood still";
  std::cout << "held start: worst position error " << worst << " m in the first 2 s\n";
}

}  // namespace
}  // namespace uampc::test
