// Lockstep runs of real scenes over Fast DDS: the motor follows the command exactly, and runs are
// deterministic, in one process or split over two.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/csv.hpp"

namespace uampc::test {
namespace {

// Runs a scene in lockstep into a fresh output directory; returns the directory.
std::string runScene(const std::string& scene, const std::string& name, int domain, const std::string& more = "") {
  const std::string out = freshDirectory(name);
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/" + scene) + " --out " + out +
                                   " --set domain_id=" + std::to_string(domain) + more);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return out;
}

constexpr double kResolution = 0.0015339807878856412;  // as in the test scenes

TEST(Lockstep, ThetaIsTheIntegralOfTheCommandWithinEncoderResolutionOver60Seconds) {
  const std::string out =
      runScene("motor_constant_speed.yaml", "lockstep_theta", testDomain(DomainBlock::kLockstep, 0));
  const auto states = run_files::readCsv(out + "/recorder_motor_states.csv").rows;
  const auto commands = run_files::readCsv(out + "/recorder_motor_commands.csv").rows;
  ASSERT_GE(states.size(), 12000u);  // 200 Hz for 60 s
  ASSERT_GE(commands.size(), 600u);  // 10 Hz for 60 s
  // Samples published in the last step (t = 60 s) would be delivered in a step that never comes.
  EXPECT_NEAR(states.back()[0], 60.0 - 0.005, 1e-9);
  // The command takes effect when it is delivered (one lockstep step after it is published);
  // the recorder receives it in the same step as the motor. Integrate the commands as applied.
  auto commandedAngle = [&](double t) {
    double theta = 0;
    for (std::size_t i = 0; i < commands.size() && commands[i][0] < t; ++i) {
      const double until = i + 1 < commands.size() ? std::min(commands[i + 1][0], t) : t;
      theta += commands[i][2] * (until - commands[i][0]);
    }
    return theta;
  };
  double worst = 0;
  for (const auto& s : states) worst = std::max(worst, std::abs(s[1] - commandedAngle(s[0])));
  EXPECT_LE(worst, kResolution / 2 + 1e-9) << "worst deviation " << worst << " rad";
  // And the encoder really quantises: positions are whole counts.
  for (const auto& s : states) EXPECT_NEAR(std::remainder(s[1], kResolution), 0.0, 1e-9);
}

// One process stepping itself (the default for a scene of one process), the same process driven by
// the launcher's clock (clock.in_process: false), and the scene split over two processes.
TEST(Lockstep, OwnClockLaunchersClockAndTwoProcessesGiveIdenticalOutputs) {
  const std::string first =
      runScene("motor_constant_speed.yaml", "lockstep_run1", testDomain(DomainBlock::kLockstep, 1));
  const std::string second = runScene("motor_constant_speed.yaml", "lockstep_run2",
                                      testDomain(DomainBlock::kLockstep, 2), " --set clock.in_process=false");
  const std::string split =
      runScene("motor_two_processes.yaml", "lockstep_split", testDomain(DomainBlock::kLockstep, 3));
  for (const char* file : {"/recorder_motor_states.csv", "/recorder_motor_commands.csv"}) {
    const std::string a = readFile(first + file);
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, readFile(second + file)) << file << " differs between the process's clock and the launcher's";
    EXPECT_EQ(a, readFile(split + file)) << file << " differs between one and two processes";
  }
}

// A process with the clock inside may finish a short run before the launcher has read its ready
// message: the launcher must see the last step among what it reads then (it waited for a step
// that never came, until clock.ack_timeout, in EveryShippedSceneStartsAndSteps).
TEST(Lockstep, ARunShorterThanTheStartEndsWithoutWaiting) {
  for (int i = 0; i < 3; ++i) {
    const std::string out = freshDirectory("lockstep_short_" + std::to_string(i));
    const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/motor_constant_speed.yaml") + " --out " +
                                     out + domainOverride(DomainBlock::kLockstep, 8) +
                                     " --set clock.duration=0.01 --set clock.ack_timeout=5");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("uampc: 0.01 s of sim time"), std::string::npos) << r.output;
  }
}

TEST(Lockstep, OverridesApplyAndShowInTheOutput) {
  // A different commanded speed must show in the output: the comparison above is not vacuous.
  const std::string out = freshDirectory("lockstep_override");
  const CommandResult r =
      runUampc("launch " + sourcePath("tests/scenes/motor_constant_speed.yaml") + " --out " + out +
               domainOverride(DomainBlock::kLockstep, 4) + " --set controller.speed=1.8 --set clock.duration=2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto states = run_files::readCsv(out + "/recorder_motor_states.csv").rows;
  ASSERT_FALSE(states.empty());
  EXPECT_NEAR(states.back()[0], 2.0 - 0.005, 1e-9);
  EXPECT_NEAR(states.back()[2], 1.8, 1e-12);
}

TEST(Lockstep, MotorFallsBackToTheSafeSpeedWhenCommandsStopAndSaysSo) {
  const std::string out = freshDirectory("lockstep_fallback");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/motor_fallback.yaml") + " --out " + out +
                                   domainOverride(DomainBlock::kLockstep, 5));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("falling back to the safe speed 1 rad/s"), std::string::npos) << r.output;
  const auto states = run_files::readCsv(out + "/recorder_motor_states.csv").rows;
  ASSERT_GT(states.size(), 300u);
  for (const auto& s : states) {
    // Still (no command yet) until the timeout passes, then the safe speed.
    if (s[0] <= 0.5) {
      EXPECT_EQ(s[2], 0.0) << "t=" << s[0];
    }
    if (s[0] >= 0.51) {
      EXPECT_DOUBLE_EQ(s[2], 1.0) << "t=" << s[0];
    }
  }
}

TEST(Lockstep, ScenesSplitOverProcessesWorkWithTheLargeDataDdsProfile) {
  const std::string out = freshDirectory("lockstep_profile");
  const CommandResult r =
      runUampc("launch " + sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " + out +
               domainOverride(DomainBlock::kLockstep, 6) +
               " --set clock.duration=2 --set dds_profile=" + sourcePath("config/dds/large_data.xml"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(run_files::readCsv(out + "/recorder_motor_states.csv").rows.size(), 300u);
  const std::string broken = freshDirectory("lockstep_profile_broken") + "/broken.xml";
  std::ofstream(broken) << "<dds><profiles><participant";
  const CommandResult bad =
      runUampc("launch " + sourcePath("tests/scenes/motor_two_processes.yaml") +
               domainOverride(DomainBlock::kLockstep, 7) + " --set clock.duration=2 --set dds_profile=" + broken);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("broken.xml: Fast DDS could not load this XML profile file"), std::string::npos)
      << bad.output;
}

// A scene spread by hand (docs/dev/time-and-lockstep.md): `uampc run-process` for each process
// group, following `uampc clock`. At the clock's end the processes end too, with exit code 0
// (before, they waited for ticks for ever); a clock stopped before the scene's end fails them, and
// they say so.
TEST(Lockstep, ProcessesStartedByHandEndWithTheirClock) {
  for (const bool stopped_early : {false, true}) {
    SCOPED_TRACE(stopped_early ? "the clock stopped early" : "the clock at its end");
    const std::string out = freshDirectory(stopped_early ? "lockstep_by_hand_stopped" : "lockstep_by_hand");
    const std::string uampc = "UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " timeout -s KILL 90 " +
                              binaryPath("bin/uampc");
    const std::string scene = sourcePath("tests/scenes/motor_two_processes.yaml");
    const std::string set = domainOverride(DomainBlock::kLockstep, stopped_early ? 10 : 9) +
                            (stopped_early ? " --set clock.duration=30 --set clock.real_time_factor=1"
                                           : " --set clock.duration=2");
    const CommandResult r = runShell(
        uampc + " run-process " + scene + " --process motor --out " + out + set + " > " + out + "/motor.log 2>&1 & m=$!; " +
        uampc + " run-process " + scene + " --process control --out " + out + set + " > " + out +
        "/control.log 2>&1 & c=$!; " + uampc + " clock " + scene + set + " > " + out + "/clock.log 2>&1 & k=$!; " +
        (stopped_early ? "sleep 6; kill -INT $k; " : "") +
        "wait $k; echo clock=$?; wait $m; echo motor=$?; wait $c; echo control=$?");
    EXPECT_NE(r.output.find(stopped_early ? "clock=130" : "clock=0"), std::string::npos) << r.output;
    for (const std::string process : {"motor", "control"}) {
      const std::string log = readFile(out + "/" + process + ".log");
      EXPECT_NE(r.output.find(process + (stopped_early ? "=1" : "=0")), std::string::npos) << r.output << log;
      EXPECT_NE(log.find(stopped_early ? "the lockstep clock left at" : "the lockstep clock ended the run"),
                std::string::npos)
          << log;
    }
  }
}

}  // namespace
}  // namespace uampc::test
