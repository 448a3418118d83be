// The whole loop over Fast DDS (map_provider, raycaster, motor_bridge, lo, mpc, evaluator): runs
// are deterministic in one process and split over three; the controller's modes do what they say;
// the evaluator writes every file; misbehaving inputs get clear, non-repeated errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/json_text.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/time_series.hpp"

namespace uampc::test {
namespace {

std::string runLoop(const std::string& scene, const std::string& name, int domain, const std::string& extra = "") {
  const std::string out = freshDirectory(name);
  const CommandResult r = runUampc("launch " + sourcePath(scene) + " --out " + out +
                                   " --set domain_id=" + std::to_string(domain) + " " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return out;
}

TEST(Loop, IdenticalOutputsTwiceAndSplitOverThreeProcesses) {
  const std::string duration = "--set clock.duration=4";
  const std::string a =
      runLoop("config/scenes/campus_ua_mpc.yaml", "loop_a", testDomain(DomainBlock::kLoop, 0), duration);
  const std::string b =
      runLoop("config/scenes/campus_ua_mpc.yaml", "loop_b", testDomain(DomainBlock::kLoop, 1), duration);
  const std::string split =
      runLoop("tests/scenes/loop_split.yaml", "loop_split", testDomain(DomainBlock::kLoop, 2), duration);
  // timings.csv holds measured computation times: the one output that is not deterministic.
  // metrics.json's "run" says where each run came from (scene, domain, time): the rest must match.
  const auto contentOf = [](const std::string& path) {
    if (path.size() < 13 || path.compare(path.size() - 13, 13, "/metrics.json") != 0) return readFile(path);
    run_files::Json metrics = run_files::readJsonFile(path);
    metrics.erase("run");
    return run_files::dumpJson(metrics);
  };
  for (const char* file : {"/metrics.json", "/estimate.tum", "/motor.csv", "/uncertainty.csv", "/cmplt_windows.csv"}) {
    const std::string reference = contentOf(a + file);
    EXPECT_GT(reference.size(), 50u) << file;
    EXPECT_EQ(reference, contentOf(b + file)) << file << " differs between two runs";
    EXPECT_EQ(reference, contentOf(split + file)) << file << " differs between one and three processes";
  }
}

TEST(Loop, ControllerModesCommandWhatTheySay) {
  const std::string base = "--set clock.duration=3 ";
  for (const auto& [mode, speed] : std::vector<std::pair<std::string, double>>{{"constant", 1.8}, {"zero", 0.0}}) {
    const std::string out =
        runLoop("config/scenes/campus_ua_mpc.yaml", "loop_" + mode, testDomain(DomainBlock::kLoop, 3),
                base + "--set controller.mode=" + mode + " --set controller.constant_speed=1.8");
    const auto motor = run_files::readRows<run_files::MotorRow>(out + "/" + run_files::kMotorFile);
    ASSERT_GT(motor.size(), 400u);
    EXPECT_NEAR(motor.back().omega, speed, 1e-6) << mode;  // after the motor's lag
    EXPECT_NEAR(motor.back().command, speed, 1e-12) << mode;
  }
  const std::string out =
      runLoop("config/scenes/campus_ua_mpc.yaml", "loop_ua_mpc", testDomain(DomainBlock::kLoop, 4), base);
  const auto motor = run_files::readRows<run_files::MotorRow>(out + "/" + run_files::kMotorFile);
  double lo = 1e9, hi = -1e9;
  for (const auto& row : motor) {
    if (row.time < 1.0) continue;  // the first scans: the local map builds up
    lo = std::min(lo, row.command);
    hi = std::max(hi, row.command);
  }
  EXPECT_GE(lo, 0.0);  // within the default bounds [0, 7.2] rad/s
  EXPECT_LE(hi, 7.2);
  EXPECT_GT(hi - lo, 0.1) << "UA-MPC never changed the speed";
  const auto profile = run_files::readUncertainty(out + "/" + run_files::kUncertaintyFile);
  ASSERT_GT(profile.size(), 10u);
  EXPECT_EQ(profile.back().samples.size(), 72u);
  for (double u : profile.back().samples) EXPECT_TRUE(std::isfinite(u));
}

// Real time reads the wall clock, the Unix epoch's seconds: every simulated component must start at
// the first time it sees, not at 0 (docs/decisions/real-time-starts-at-the-first-time.md). The
// default scene (IMU on) used to spin in the IMU's noise from sample 0 until the stop, and
// without the IMU it cast no scan (frames from t = 0) and played the trajectory's last pose.
TEST(Loop, TheDefaultSceneInRealTimeEvaluatesItsPoses) {
  const std::string out = runLoop("config/scenes/default.yaml", "loop_realtime", testDomain(DomainBlock::kLoop, 10),
                                  "--set clock.mode=realtime --set clock.duration=10");
  const auto metrics = run_files::readMetricsFile(out + "/metrics.json");
  ASSERT_TRUE(metrics) << readFile(out + "/metrics.json");
  EXPECT_GT(metrics->trajectory.paired, 0u);
  EXPECT_TRUE(std::isfinite(metrics->trajectory.ate.unaligned_m.rmse));
  EXPECT_GT(metrics->cmplt_ground_truth.scans, 0u);
}

TEST(Loop, EvaluatorWritesEveryFileAndTheLoStaysOnTrack) {
  const std::string out = runLoop("config/scenes/campus_ua_mpc.yaml", "loop_eval", testDomain(DomainBlock::kLoop, 5),
                                  "--set clock.duration=10 --set evaluator.panorama_period=4");
  for (const char* file :
       {"metrics.json", "estimate.tum", "ground_truth.tum", "ate.csv", "cmplt_windows.csv",
        "cmplt_ground_truth_windows.csv", "motor.csv", "timings.csv", "uncertainty.csv", "scanned_voxels.bt"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + file)) << file;
  }
  const auto ate = run_files::readRows<run_files::AteRow>(out + "/" + run_files::kAteFile);
  ASSERT_GT(ate.size(), 90u);  // 10 Hz for 10 s
  double worst = 0;
  for (const auto& row : ate) worst = std::max(worst, row.ate_m);
  EXPECT_LT(worst, 0.5) << "the LO drifted more than 0.5 m in 10 s on the campus";
  const std::string metrics = readFile(out + "/metrics.json");
  EXPECT_NE(metrics.find("\"cmplt_ground_truth\""), std::string::npos);
  // A panorama snapshot every 4 s: at 4 s and 8 s, 180 x 90 RGB pixels stored uncompressed.
  std::vector<std::string> snapshots;
  for (const auto& entry : std::filesystem::directory_iterator(out + "/panorama")) {
    snapshots.push_back(entry.path().filename().string());
  }
  std::sort(snapshots.begin(), snapshots.end());
  ASSERT_EQ(snapshots.size(), 2u);
  EXPECT_EQ(snapshots[0].rfind("panorama_00004.", 0), 0u) << snapshots[0];
  EXPECT_EQ(snapshots[1].rfind("panorama_00008.", 0), 0u) << snapshots[1];
  const std::string png = readFile(out + "/panorama/" + snapshots[0]);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_GT(png.size(), 180u * 90u * 3u);
}

TEST(Loop, ScansWithoutTimeFieldAreReportedOnceNotPerMessage) {
  const std::string out = freshDirectory("lo_bad_no_time");
  const CommandResult r =
      runUampc("launch " + sourcePath("tests/scenes/lo_bad_scans.yaml") + domainOverride(DomainBlock::kLoop, 6));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string needle = "cannot use scans on /lidar/points: no per-point time field";
  const auto first = r.output.find(needle);
  EXPECT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(needle, first + 1), std::string::npos) << "said more than once:\n" << r.output;
  // The controller, without a local map, says so and keeps the preferred speed.
  EXPECT_NE(r.output.find("commanding omega_pre 3.6 rad/s"), std::string::npos) << r.output;
}

// Raw scans with NaN and infinite point times: those points are skipped, the rest placed with
// ground truth. An infinite time used to hold the scan back for good (it never became
// "covered"), and every later scan behind it: no ground-truth CMPLT at all.
TEST(Loop, EvaluatorSkipsPointsWithNonFiniteTimes) {
  const std::string out = freshDirectory("evaluator_bad_scans");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/evaluator_bad_scans.yaml") + " --out " + out +
                                   domainOverride(DomainBlock::kLoop, 9));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string metrics = readFile(out + "/metrics.json");
  const auto gt = metrics.find("\"cmplt_ground_truth\"");
  ASSERT_NE(gt, std::string::npos) << metrics;
  const auto scans = metrics.find("\"scans\":", gt);
  ASSERT_NE(scans, std::string::npos) << metrics;
  EXPECT_GE(std::stoi(metrics.substr(scans + 8)), 50) << metrics;  // ~60 scans in 6 s, all placed
  EXPECT_NE(r.output.find("have points with non-finite times"), std::string::npos) << r.output;
}

TEST(Loop, EveryShippedSceneStartsAndSteps) {
  // Without --out, as a user's first try would be; the MCD scenes read data/mcd. Each starts without
  // a warning (the scenes declare what they leave unread or unfed: docs/user/scenes.md, "Topics").
  for (const auto& entry : std::filesystem::directory_iterator(sourcePath("config/scenes"))) {
    if (entry.path().extension() != ".yaml") continue;
    // replay_lo needs a recording: record_replay_test runs it on one.
    if (entry.path().filename() == "replay_lo.yaml") continue;
    // rig_mid360 drives a servo on a serial port: dynamixel_bridge_test runs it on the emulator.
    if (entry.path().filename() == "rig_mid360.yaml") continue;
    const CommandResult r = runUampc("launch " + entry.path().string() + domainOverride(DomainBlock::kLoop, 8) +
                                     " --set clock.duration=0.2");
    EXPECT_EQ(r.exit_code, 0) << entry.path() << "\n" << r.output;
    EXPECT_EQ(startWarnings(r.output), "") << entry.path();
  }
}

TEST(Loop, MalformedPanoramasAreReportedOnceAndNotSaved) {
  for (const char* mode : {"wrong_encoding", "short_data"}) {
    const std::string out = freshDirectory(std::string("bad_panorama_") + mode);
    const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/evaluator_bad_panorama.yaml") + " --out " +
                                     out + domainOverride(DomainBlock::kLoop, 8) + " --set controller.mode=" + mode);
    EXPECT_EQ(r.exit_code, 0) << mode << "\n" << r.output;
    const std::string needle = "ignoring panoramas on /mpc/panorama: expected little-endian 32FC1";
    const auto first = r.output.find(needle);
    EXPECT_NE(first, std::string::npos) << mode << "\n" << r.output;
    EXPECT_EQ(r.output.find(needle, first + 1), std::string::npos) << "said more than once:\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(out + "/panorama")) << mode;
  }
}

TEST(Loop, DeclaredPortNeverOpenedIsAnErrorNotAStall) {
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/evaluator_bad_panorama.yaml") +
                                   domainOverride(DomainBlock::kLoop, 8) + " --set controller.mode=never_opened");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("component 'controller' (bad_panorama_publisher) declares port 'panorama' but did not "
                          "open it in its constructor"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("no ready message"), std::string::npos) << "waited for the stalled start:\n" << r.output;
}

TEST(Loop, NanPointsAndEmptyScansAreSurvived) {
  for (const char* mode : {"nan_points", "empty"}) {
    const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/lo_bad_scans.yaml") +
                                     domainOverride(DomainBlock::kLoop, 7) + " --set driver.mode=" + mode);
    EXPECT_EQ(r.exit_code, 0) << mode << "\n" << r.output;
    if (std::string(mode) == "nan_points") {
      EXPECT_NE(r.output.find("contain non-finite points; they are dropped"), std::string::npos) << r.output;
    }
  }
}

}  // namespace
}  // namespace uampc::test
