// The motor bridge's DYNAMIXEL backend in real-time runs of `uampc launch` against an emulated
// XM430 on a pseudo-terminal (tools/dynamixel_emulator), hosted by this test: velocity tracking,
// a cable pulled and plugged back mid-run, a wrong ID at start, lockstep refused; and the rig
// scene (config/scenes/rig_mid360.yaml) on the emulator with `uampc play --restamp` of a recorded
// simulation standing in for the Livox driver.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <thread>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "servo_emulator.hpp"
#include "test_domains.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/recording/playback.hpp"
#include "uampc/run_files/csv.hpp"
#include "uampc/runtime/typed_sample.hpp"

namespace uampc::test {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

dynamixel::EmulatorOptions emulated(const std::string& name) {
  dynamixel::EmulatorOptions o;
  o.link =
      (std::filesystem::temp_directory_path() / ("uampc_dxl_e2e_" + name + "_" + std::to_string(getpid()))).string();
  o.model = "XM430-W350";
  o.velocity_limit = 265;
  o.max_acceleration = 50.0;
  return o;
}

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

template <typename Message>
Message decode(const SerializedMessage& sample) {
  Message message;
  EXPECT_TRUE(decodeSample(sample, message));
  return message;
}

// What the rig's recorder heard, by topic: (log time on arrival, header stamp).
std::map<std::string, std::vector<std::pair<Time, Time>>> arrivals(const std::string& file) {
  recording::Playback playback(file, {});
  std::map<std::string, std::vector<std::pair<Time, Time>>> by_topic;
  recording::RecordedSample sample;
  while (playback.next(playback.end(), sample)) {
    const std::string& topic = playback.topics()[sample.topic].topic;
    Time stamp;
    if (topic == "/livox/lidar") stamp = fromMsg(decode<sensor_msgs::msg::PointCloud2>(sample.data).header().stamp());
    if (topic == "/lo/odometry") stamp = fromMsg(decode<nav_msgs::msg::Odometry>(sample.data).header().stamp());
    by_topic[topic].push_back({sample.time, stamp});
  }
  return by_topic;
}

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<std::size_t>(p * (values.size() - 1) + 0.5))];
}

// The rig scene as it runs on hardware, with the emulator for the servo and a recorded simulation
// in livox_ros_driver2's layout for the LiDAR. The scans were taken at another motor's angles, so
// the odometry says nothing about accuracy; what is checked is that every part works together in
// real time, and the latency from a scan's arrival to the motor command it leads to is measured.
TEST(DynamixelBridge, TheRigSceneRunsOnARecordedLidarAndTheEmulatedServo) {
  const std::string dir = freshDirectory("dynamixel_rig");
  const CommandResult sim = runUampc("launch " + sourcePath("tests/scenes/record_livox.yaml") + " --out " + dir +
                                     "/sim" + domainOverride(DomainBlock::kDynamixel, 4));
  ASSERT_EQ(sim.exit_code, 0) << sim.output;

  dynamixel::EmulatorOptions servo = emulated("rig");
  servo.model = "XM430-W210";
  servo.velocity_limit = 330;  // 7.9 rad/s
  dynamixel::ServoEmulator emulator(servo);
  const int domain = testDomain(DomainBlock::kDynamixel, 5);
  // The emulator shares two cores with the LO, the MPC, the player and another test here: a reply
  // can come far later than the default reply_timeout (10 ms, sized for a real servo), so allow 200.
  const pid_t rig = startLaunch(sourcePath("config/scenes/rig_mid360.yaml") + " --set motor.port=" + emulator.port() +
                                    " --set motor.reply_timeout=0.2" + " --set clock.duration=14 --out " + dir +
                                    "/rig --set domain_id=" + std::to_string(domain),
                                dir + "/rig.log");
  const CommandResult play =
      runUampc("play " + dir + "/sim/recording.mcap --restamp --wait-for-readers --domain " + std::to_string(domain));
  EXPECT_EQ(play.exit_code, 0) << play.output;
  ASSERT_EQ(exitCodeOf(rig), 0) << readFile(dir + "/rig.log");
  const std::string log = readFile(dir + "/rig.log");
  EXPECT_EQ(log.find("ERROR"), std::string::npos) << log;
  EXPECT_EQ(log.find("s rejected:"), std::string::npos) << log;  // no scan refused: its times were understood

  const auto heard = arrivals(dir + "/rig/recording.mcap");
  const auto& scans = heard.at("/livox/lidar");
  const auto& odometry = heard.at("/lo/odometry");
  const auto& commands = heard.at("/motor/command");
  // 6 s at 10 Hz, 60 scans; best-effort on a loaded machine loses some.
  EXPECT_GE(scans.size(), 40u);
  EXPECT_GE(odometry.size(), 30u);
  EXPECT_GE(heard.at("/motor/state").size(), 1400u);  // 14 s at 200 Hz, less the start and a loaded machine
  EXPECT_GT(emulator.packetsReceived(), 2000u);

  // Scan arrival -> the first command published after the odometry of that scan (the bridge writes
  // each command on the bus as it arrives: one 16-byte write, 0.3 ms at 1 Mbps).
  std::vector<double> latencies;
  for (const auto& [odometry_arrival, odometry_stamp] : odometry) {
    const auto scan =
        std::find_if(scans.rbegin(), scans.rend(), [&](const auto& s) { return s.second <= odometry_stamp; });
    const auto command =
        std::find_if(commands.begin(), commands.end(), [&](const auto& c) { return c.first >= odometry_arrival; });
    if (scan == scans.rend() || command == commands.end()) continue;
    latencies.push_back((command->first - scan->first).seconds());
  }
  ASSERT_GE(latencies.size(), 25u);
  std::cout << "scan arrival to motor command, " << latencies.size() << " scans: median "
            << percentile(latencies, 0.5) * 1e3 << " ms, p99 " << percentile(latencies, 0.99) * 1e3 << " ms\n";
}

}  // namespace
}  // namespace uampc::test
