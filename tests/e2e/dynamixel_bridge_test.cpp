// The motor bridge's DYNAMIXEL backend in real-time runs of `uampc launch` against an emulated
// XM430 on a pseudo-terminal (tools/dynamixel_emulator), hosted by this test: velocity tracking,
// a cable pulled and plugged back mid-run, a hardware error, the safe speed without commands, a
// wrong ID at start, lockstep refused. rig_scene_test runs the whole rig scene.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "emulated_servo.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/csv.hpp"

namespace uampc::test {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

std::string launchArguments(const dynamixel::ServoEmulator& emulator, int domain_index, const std::string& out,
                            const std::string& extra = "") {
  return sourcePath("tests/scenes/dynamixel_constant_speed.yaml") + " --out " + out +
         " --set motor.port=" + emulator.port() + extra + domainOverride(DomainBlock::kDynamixel, domain_index);
}

// stamp, position, velocity
std::vector<std::vector<double>> motorStates(const std::string& out) {
  return run_files::readCsv(out + "/recorder_motor_states.csv").rows;
}

TEST(DynamixelBridge, DrivesTheServoAtTheCommandedSpeedInRealTime) {
  dynamixel::ServoEmulator emulator(emulated("track"));
  const std::string out = freshDirectory("dynamixel_track");
  const CommandResult run = runUampc("launch " + launchArguments(emulator, 0, out));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("DYNAMIXEL XM430-W350 ID 1 on " + emulator.port()), std::string::npos) << run.output;
  const auto rows = motorStates(out);
  ASSERT_GT(rows.size(), 200u);  // 3 s at 200 Hz, less the start
  const double end = rows.back()[0];
  int late = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GT(rows[i][0], rows[i - 1][0]) << "row " << i;
    EXPECT_GE(rows[i][1], rows[i - 1][1] - 1e-9) << "row " << i;  // turning one way
    if (rows[i][0] > end - 1.0) {
      EXPECT_NEAR(rows[i][2], 3.0, 0.03) << "row " << i;  // one velocity unit is 0.024 rad/s
      ++late;
    }
  }
  EXPECT_GT(late, 100);
  EXPECT_FALSE(emulator.torqueEnabled());  // released when the run ended
}

TEST(DynamixelBridge, APulledCableIsReportedTheServoStopsAndTheRunRecovers) {
  dynamixel::ServoEmulator emulator(emulated("unplug"));
  const std::string out = freshDirectory("dynamixel_unplug");
  const pid_t launcher = startLaunch(launchArguments(emulator, 1, out, " --set clock.duration=6"), out + ".log");
  ASSERT_TRUE(waitFor([&] { return std::abs(emulator.velocity() - 3.0) < 0.05; }, seconds(30)))
      << readFile(out + ".log");
  std::this_thread::sleep_for(milliseconds(500));
  emulator.unplug();
  std::this_thread::sleep_for(milliseconds(800));
  // The bridge cannot reach it; the servo's bus watchdog (0.5 s) has stopped it.
  EXPECT_TRUE(emulator.watchdogTripped());
  EXPECT_LT(std::abs(emulator.velocity()), 0.05);
  emulator.replug();
  EXPECT_EQ(exitCodeOf(launcher), 0) << readFile(out + ".log");
  const std::string log = readFile(out + ".log");
  EXPECT_NE(log.find("DYNAMIXEL bus lost"), std::string::npos) << log;
  EXPECT_NE(log.find("answers again after"), std::string::npos) << log;

  // No state while the bus was lost, then the commanded speed again.
  const auto rows = motorStates(out);
  double gap = 0, gap_end = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i][0] - rows[i - 1][0] > gap) {
      gap = rows[i][0] - rows[i - 1][0];
      gap_end = rows[i][0];
    }
  }
  std::cout << "encoder states missing for " << gap << " s around an 0.8 s unplug\n";
  EXPECT_GT(gap, 0.7);
  EXPECT_LT(gap, 2.0);
  EXPECT_NEAR(rows.back()[2], 3.0, 0.03);
  EXPECT_GT(rows.back()[0], gap_end + 1.0);
}

TEST(DynamixelBridge, AHardwareErrorMidRunIsNamed) {
  dynamixel::ServoEmulator emulator(emulated("hardware_error"));
  const std::string out = freshDirectory("dynamixel_hardware_error");
  const pid_t launcher = startLaunch(launchArguments(emulator, 6, out), out + ".log");
  ASSERT_TRUE(waitFor([&] { return std::abs(emulator.velocity() - 3.0) < 0.05; }, seconds(30)))
      << readFile(out + ".log");
  emulator.setHardwareError(0x24);     // overheating and overload
  EXPECT_EQ(exitCodeOf(launcher), 0);  // the run goes on; the servo has let go
  const std::string log = readFile(out + ".log");
  EXPECT_NE(log.find("reports a hardware error: overheating, overload; the servo has turned its torque off"),
            std::string::npos)
      << log;
  EXPECT_FALSE(emulator.torqueEnabled());
  const auto rows = motorStates(out);
  ASSERT_FALSE(rows.empty());
  EXPECT_LT(std::abs(rows.back()[2]), 0.05);  // still read: the motor has coasted to rest
}

TEST(DynamixelBridge, FallsBackToTheSafeSpeedWithoutCommands) {
  dynamixel::ServoEmulator emulator(emulated("fallback"));
  const std::string out = freshDirectory("dynamixel_fallback");
  const CommandResult run =
      runUampc("launch " + sourcePath("tests/scenes/dynamixel_fallback.yaml") + " --out " + out +
               " --set motor.port=" + emulator.port() + domainOverride(DomainBlock::kDynamixel, 7));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("falling back to the safe speed 1.5 rad/s"), std::string::npos) << run.output;
  EXPECT_NEAR(emulator.goalVelocity(), 1.5, 0.03);
}

TEST(DynamixelBridge, AWrongIdStartsNothingAndNamesPortAndId) {
  dynamixel::ServoEmulator emulator(emulated("wrong_id"));
  const std::string out = freshDirectory("dynamixel_wrong_id");
  const CommandResult run = runUampc("launch " + launchArguments(emulator, 2, out, " --set motor.id=9"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find("no DYNAMIXEL answered as ID 9 on " + emulator.port() + " at 1000000 baud"),
            std::string::npos)
      << run.output;
}

TEST(DynamixelBridge, RefusesLockstep) {
  dynamixel::ServoEmulator emulator(emulated("lockstep"));
  const std::string out = freshDirectory("dynamixel_lockstep");
  const CommandResult run = runUampc("launch " + launchArguments(emulator, 3, out, " --set clock.mode=lockstep"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find("backend 'dynamixel' drives a real motor and needs clock.mode: realtime"),
            std::string::npos)
      << run.output;
  EXPECT_FALSE(emulator.torqueEnabled());
}

}  // namespace
}  // namespace uampc::test
