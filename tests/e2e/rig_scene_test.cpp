// config/scenes/rig_mid360.yaml as it runs on hardware, in real time: the emulated servo
// (tools/dynamixel_emulator) for the motor, and `uampc play --restamp` of a simulation recorded in
// livox_ros_driver2's layout for the LiDAR. Apart from dynamixel_bridge_test because it runs the LO
// and UA-MPC in real time, which a sanitizer build is too slow for (docs/dev/testing.md,
// "Sanitizers and CI").
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "emulated_servo.hpp"
#include "test_domains.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/recording/playback.hpp"
#include "uampc/runtime/typed_sample.hpp"

namespace uampc::test {
namespace {

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

// What a run in real time must deliver at least.
struct RealTimeCounts {
  std::size_t scans, odometry, motor_states, servo_packets, latencies;
};

#ifdef __SANITIZE_THREAD__  // GCC's mark of -fsanitize=thread (UAMPC_SANITIZE=thread)
constexpr bool kUnderThreadSanitizer = true;
#else
constexpr bool kUnderThreadSanitizer = false;
#endif

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
                                     "/sim" + domainOverride(DomainBlock::kRigScene, 0));
  ASSERT_EQ(sim.exit_code, 0) << sim.output;

  dynamixel::EmulatorOptions servo = emulated("rig");
  servo.model = "XM430-W210";
  servo.velocity_limit = 330;  // 7.9 rad/s
  dynamixel::ServoEmulator emulator(servo);
  const int domain = testDomain(DomainBlock::kRigScene, 1);
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
  EXPECT_EQ(startWarnings(log), "");                             // its unfed and external inputs are declared
  EXPECT_EQ(log.find("s rejected:"), std::string::npos) << log;  // no scan refused: its times were understood

  const auto heard = arrivals(dir + "/rig/recording.mcap");
  const auto& scans = heard.at("/livox/lidar");
  const auto& odometry = heard.at("/lo/odometry");
  const auto& commands = heard.at("/motor/command");
  // 6 s at 10 Hz, 60 scans; best-effort on a loaded machine loses some. ThreadSanitizer's build runs
  // the LO and UA-MPC several times slower than real time, and its runs kept 32-38 scans and 1369
  // motor states (2026-11-28): there the run must still work, race-free, at a lower rate.
  const RealTimeCounts expected = kUnderThreadSanitizer ? RealTimeCounts{20, 15, 1000, 1000, 10}
                                                        : RealTimeCounts{40, 30, 1400, 2000, 25};
  EXPECT_GE(scans.size(), expected.scans);
  EXPECT_GE(odometry.size(), expected.odometry);
  EXPECT_GE(heard.at("/motor/state").size(), expected.motor_states);  // 14 s at 200 Hz, less the start
  EXPECT_GT(emulator.packetsReceived(), expected.servo_packets);

  // Scan arrival -> the first command published after the odometry of that scan (the bridge writes
  // each command on the bus as it arrives: one 16-byte write, 0.3 ms at 1 Mbps).
  std::vector<double> latencies;
  for (const auto& odometry_sample : odometry) {
    const Time arrival = odometry_sample.first, stamp = odometry_sample.second;  // lambdas cannot capture bindings
    const auto scan = std::find_if(scans.rbegin(), scans.rend(), [&](const auto& s) { return s.second <= stamp; });
    const auto command =
        std::find_if(commands.begin(), commands.end(), [&](const auto& c) { return c.first >= arrival; });
    if (scan == scans.rend() || command == commands.end()) continue;
    latencies.push_back((command->first - scan->first).seconds());
  }
  ASSERT_GE(latencies.size(), expected.latencies);
  std::cout << "scan arrival to motor command, " << latencies.size() << " scans: median "
            << percentile(latencies, 0.5) * 1e3 << " ms, p99 " << percentile(latencies, 0.99) * 1e3 << " ms\n";
}

}  // namespace
}  // namespace uampc::test
