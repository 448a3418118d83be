// What an experiment counts as a finished run (docs/user/experiments.md, "What counts as done"):
// `uampc launch` exited 0 and its metrics.json's sim time reached the scene's end. A run cut
// short (its launcher terminated, or metrics that stop early) is failed, named, left out of the
// table and run again on resume; so is a directory holding both a done and a failed marker.
#include <gtest/gtest.h>
#include <signal.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "../e2e/background_launch.hpp"
#include "../e2e/command_runner.hpp"
#include "motor_experiment.hpp"
#include "uampc/run_files/metrics_file.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

YAML::Node onlyRun(const std::string& out) { return YAML::LoadFile(out + "/results.json")["runs"][0]; }

void setMetricsSimTime(const std::string& run, double sim_time) {
  const std::string path = run + "/metrics.json";
  auto metrics = run_files::readMetricsFile(path);
  ASSERT_TRUE(metrics) << path;
  metrics->sim_time = sim_time;
  run_files::writeMetricsFile(path, *metrics);
}

// The reported case: the launcher got SIGTERM 2.7 s into a 30 s run, exited 0 and wrote its
// metrics, and the run was taken for done ("ok", sim_time_s 2.7). The run is paced in real time so
// that it is still running when the signal comes.
TEST(RunDone, ARunWhoseLauncherIsTerminatedIsNotCountedDone) {
  const MotorExperiment e = motorExperiment(freshDirectory("run_done_terminated"), 30, true, 3);
  const pid_t experiment = startUampc(e.command(), e.out + ".log");
  ASSERT_TRUE(waitFor([&] { return runIsStepping(e); }, std::chrono::seconds(60))) << readFile(e.out + ".log");
  const pid_t launcher = launcherOnDomain(e.domain);
  ASSERT_GT(launcher, 0);
  ASSERT_EQ(kill(launcher, SIGTERM), 0);
  EXPECT_EQ(exitCodeOf(experiment), 1) << readFile(e.out + ".log");

  const std::string output = readFile(e.out + ".log");
  EXPECT_NE(output.find("runs/motor/constant/seed1 failed"), std::string::npos) << output;
  const YAML::Node run = onlyRun(e.out);
  EXPECT_EQ(run["status"].as<std::string>(), "failed");
  EXPECT_FALSE(fs::exists(e.run + "/done"));
  EXPECT_TRUE(fs::exists(e.run + "/failed"));
  // Not counted in the table: no finished run of the scene.
  EXPECT_NE(readFile(e.out + "/results.md").find("| constant | 0 lost of 0 |"), std::string::npos)
      << readFile(e.out + "/results.md");
}

// metrics.json that stops short of the scene's end, under a done marker (what an older uampc
// left, or a launcher that exits 0 when cut): --collect names the run as failed, and a resume runs
// it again.
TEST(RunDone, MetricsThatStopShortOfTheSceneEndAreNotDoneAndAreRunAgain) {
  const MotorExperiment e = motorExperiment(freshDirectory("run_done_short_metrics"), 2, false, 4);
  const CommandResult first = runUampc(e.command());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  ASSERT_EQ(onlyRun(e.out)["status"].as<std::string>(), "ok");
  ASSERT_TRUE(fs::exists(e.run + "/done"));
  setMetricsSimTime(e.run, 1.2);

  const CommandResult collected = runUampc("experiment --collect " + e.out);
  EXPECT_EQ(collected.exit_code, 1) << collected.output;
  EXPECT_NE(collected.output.find("runs/motor/constant/seed1"), std::string::npos) << collected.output;
  EXPECT_NE(collected.output.find("1.2 s of 2 s"), std::string::npos) << collected.output;
  EXPECT_EQ(onlyRun(e.out)["status"].as<std::string>(), "failed");

  const CommandResult resumed = runUampc(e.command());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("retrying runs/motor/constant/seed1"), std::string::npos) << resumed.output;
  EXPECT_EQ(onlyRun(e.out)["status"].as<std::string>(), "ok");
  EXPECT_DOUBLE_EQ(onlyRun(e.out)["sim_time_s"].as<double>(), 2.0);
}

// A run directory with both markers (two attempts wrote into it, the reported race of two
// experiments on one --out) is not done, and the next attempt starts without either.
TEST(RunDone, ADirectoryWithBothMarkersIsNotDoneAndIsRunAgainWithoutThem) {
  const MotorExperiment e = motorExperiment(freshDirectory("run_done_both_markers"), 2, false, 5);
  ASSERT_EQ(runUampc(e.command()).exit_code, 0);
  std::ofstream(e.run + "/failed") << "exit code 1\n";

  const CommandResult collected = runUampc("experiment --collect " + e.out);
  EXPECT_EQ(collected.exit_code, 1) << collected.output;
  EXPECT_NE(onlyRun(e.out)["status"].as<std::string>(), "ok");

  const CommandResult resumed = runUampc(e.command());
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("retrying runs/motor/constant/seed1"), std::string::npos) << resumed.output;
  EXPECT_TRUE(fs::exists(e.run + "/done"));
  EXPECT_FALSE(fs::exists(e.run + "/failed"));
}

}  // namespace
}  // namespace uampc::test
