// The faults a real bus has, injected into the emulated servo and seen from the host's side of
// the link: corrupted packets both ways, a silent servo, a hardware error, an unplugged adapter.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include "host_port.hpp"
#include "servo_emulator.hpp"

namespace uampc::dynamixel::test {
namespace {

const Packet kPing{1, instruction::kPing, {}};

TEST(DynamixelEmulatorFaults, CorruptsTheNextReplies) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  servo.corruptReplies(2);
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(host.writeBytes(encode(kPing)));
    const auto result = host.receive();
    ASSERT_TRUE(result);
    EXPECT_EQ(result->kind, PacketParser::Result::Kind::kCrcError);
  }
  EXPECT_EQ(host.request(kPing).params[0], 0);  // the third is intact
}

TEST(DynamixelEmulatorFaults, AnswersACorruptedInstructionWithACrcError) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  Bytes corrupted = encode(writePacket(1, table::kGoalVelocity, 10));
  corrupted[9] ^= 0x01;
  ASSERT_TRUE(host.writeBytes(corrupted));
  const auto result = host.receive();
  ASSERT_TRUE(result);
  ASSERT_EQ(result->kind, PacketParser::Result::Kind::kPacket);
  EXPECT_EQ(result->packet.params[0], 3);  // CRC error
  EXPECT_EQ(servo.corruptPacketsReceived(), 1u);
  EXPECT_EQ(host.readField(table::kGoalVelocity), 0u);  // not written
  EXPECT_EQ(servo.packetsReceived(), 1u);               // the READ
  EXPECT_EQ(servo.bytesReceived(), corrupted.size() + 14u);
}

TEST(DynamixelEmulatorFaults, ASilentServoNeitherAnswersNorActs) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  servo.setSilent(true);
  ASSERT_TRUE(host.writeBytes(encode(writePacket(1, table::kGoalVelocity, 10))));
  EXPECT_TRUE(host.readBytes(1, 50ms).empty());
  EXPECT_TRUE(eventually([&] { return servo.packetsReceived() == 1u; }));
  EXPECT_EQ(servo.bytesSent(), 0u);
  servo.setSilent(false);
  EXPECT_EQ(host.readField(table::kGoalVelocity), 0u);
}

TEST(DynamixelEmulatorFaults, HardwareErrorAlertsKeepsTheTorqueOffUntilReboot) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  ASSERT_EQ(host.writeField(table::kTorqueEnable, 1), 0);
  servo.setHardwareError(0x20);  // overload
  EXPECT_FALSE(servo.torqueEnabled());
  EXPECT_EQ(host.request(kPing).params[0], kAlertBit);
  EXPECT_EQ(host.readField(table::kHardwareErrorStatus), 0x20u);  // the alert does not fail a READ
  EXPECT_EQ(host.readField(table::kTorqueEnable), 0u);
  EXPECT_EQ(host.writeField(table::kTorqueEnable, 1), kAlertBit | 7);  // access error
  servo.setHardwareError(0);                                           // clears nothing
  EXPECT_EQ(host.readField(table::kHardwareErrorStatus), 0x20u);

  host.request(Packet{1, instruction::kReboot, {}});
  EXPECT_EQ(host.request(kPing).params[0], 0);
  EXPECT_EQ(host.readField(table::kHardwareErrorStatus), 0u);
  EXPECT_EQ(host.writeField(table::kTorqueEnable, 1), 0);
  EXPECT_TRUE(servo.torqueEnabled());
}

TEST(DynamixelEmulatorFaults, UnplugFailsTheHostAndReplugPowerCycles) {
  EmulatorOptions options = optionsWithLink();
  options.initial_position = 5000;
  ServoEmulator servo(options);
  HostPort host(servo.port());
  ASSERT_EQ(host.writeField(table::kTorqueEnable, 1), 0);
  ASSERT_EQ(host.writeField(table::kBusWatchdog, 100), 0);
  ASSERT_EQ(host.writeField(table::kGoalVelocity, 50), 0);

  servo.unplug();
  EXPECT_FALSE(std::filesystem::is_symlink(servo.port()));
  EXPECT_LT(::open(servo.port().c_str(), O_RDWR | O_NOCTTY), 0);
  std::uint8_t byte = 0;
  EXPECT_LE(::read(host.fd(), &byte, 1), 0);  // hung up: end of file or EIO
  EXPECT_FALSE(host.writeBytes(encode(kPing)));

  servo.replug();
  HostPort again(servo.port());
  EXPECT_EQ(again.request(kPing).params[0], 0);
  EXPECT_FALSE(servo.torqueEnabled());
  EXPECT_EQ(again.readField(table::kTorqueEnable), 0u);
  EXPECT_EQ(again.readField(table::kGoalVelocity), 0u);
  EXPECT_EQ(again.readField(table::kBusWatchdog), 0u);
  EXPECT_EQ(again.readField(table::kPresentPosition), 5000u % 4096u);  // within one turn
  EXPECT_EQ(again.readField(table::kOperatingMode), 3u);               // EEPROM kept (never written)
}

// A host hammering the port while the adapter comes and goes: nothing hangs or crashes, and the
// servo answers once it is back.
TEST(DynamixelEmulatorFaults, SurvivesUnplugAndReplugDuringTraffic) {
  ServoEmulator servo(optionsWithLink());
  std::atomic<bool> done{false};
  std::thread traffic([&] {
    while (!done) {
      try {
        HostPort host(servo.port());
        while (!done && host.writeBytes(encode(kPing))) host.receive(20ms);
      } catch (const std::exception&) {
        std::this_thread::sleep_for(1ms);  // unplugged: try the link again
      }
    }
  });
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(10ms);
    servo.unplug();
    std::this_thread::sleep_for(5ms);
    servo.replug();
  }
  done = true;
  traffic.join();
  HostPort host(servo.port());
  EXPECT_EQ(host.request(kPing).params[0], 0);
  EXPECT_GT(servo.packetsReceived(), 1u);
}

TEST(DynamixelEmulatorFaults, RefusesBadOptionsClearly) {
  EmulatorOptions unknown_model = optionsWithLink();
  unknown_model.model = "XM999";
  try {
    ServoEmulator servo(unknown_model);
    FAIL() << "an unknown model was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("XM430-W350"), std::string::npos) << e.what();  // lists the known
  }
  EXPECT_THROW(ServoEmulator(EmulatorOptions{}), std::runtime_error);  // no link
  EmulatorOptions no_directory = optionsWithLink();
  no_directory.link += "/missing/port";
  EXPECT_THROW(ServoEmulator{no_directory}, std::runtime_error);
  EmulatorOptions regular_file = optionsWithLink();
  std::ofstream(regular_file.link) << "not a port";
  EXPECT_THROW(ServoEmulator{regular_file}, std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_regular_file(regular_file.link));  // left alone
  std::filesystem::remove(regular_file.link);
}

TEST(DynamixelEmulatorFaults, RemovesItsLinkWhenDestroyed) {
  const EmulatorOptions options = optionsWithLink();
  {
    ServoEmulator servo(options);
    EXPECT_TRUE(std::filesystem::is_symlink(options.link));
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(options.link)));
}

}  // namespace
}  // namespace uampc::dynamixel::test
