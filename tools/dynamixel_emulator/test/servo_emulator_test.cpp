// The emulated servo against the X-series e-manual, through its link only: what a host sees on
// the wire (byte-exact where the manual gives bytes), the write rules, and the motor behind it.
#include <gtest/gtest.h>

#include <limits>
#include <thread>

#include "host_port.hpp"
#include "servo_emulator.hpp"

namespace uampc::dynamixel::test {
namespace {

constexpr Field kMoving{122, 1};

// Velocity mode with the torque on, as the bridge sets the servo up.
void startVelocityControl(HostPort& host) {
  ASSERT_EQ(host.writeField(table::kOperatingMode, kVelocityControlMode), 0);
  ASSERT_EQ(host.writeField(table::kTorqueEnable, 1), 0);
}

TEST(DynamixelEmulator, AnswersPingWithTheManualsBytes) {
  EmulatorOptions options = optionsWithLink();
  options.model = "XM430-W210";  // 1030
  options.firmware = 0x26;
  ServoEmulator servo(options);
  HostPort host(servo.port());
  const Bytes expected{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x55, 0x00, 0x06, 0x04, 0x26, 0x65, 0x5D};
  ASSERT_TRUE(host.writeBytes(encode(Packet{1, instruction::kPing, {}})));
  EXPECT_EQ(host.readBytes(expected.size(), 1000ms), expected);
  // Broadcast PING is answered too, with the servo's own ID.
  ASSERT_TRUE(host.writeBytes(encode(Packet{kBroadcastId, instruction::kPing, {}})));
  EXPECT_EQ(host.readBytes(expected.size(), 1000ms), expected);
}

TEST(DynamixelEmulator, AnswersOnlyItsIdAndOnlyPingOnBroadcast) {
  EmulatorOptions options = optionsWithLink();
  options.id = 3;
  ServoEmulator servo(options);
  HostPort host(servo.port());
  ASSERT_TRUE(host.writeBytes(encode(Packet{1, instruction::kPing, {}})));
  EXPECT_TRUE(host.readBytes(1, 50ms).empty());
  ASSERT_TRUE(host.writeBytes(encode(readPacket(kBroadcastId, table::kModelNumber))));
  EXPECT_TRUE(host.readBytes(1, 50ms).empty());
  // A broadcast WRITE is executed all the same, unanswered.
  ASSERT_TRUE(host.writeBytes(encode(writePacket(kBroadcastId, table::kGoalVelocity, 7))));
  EXPECT_TRUE(host.readBytes(1, 50ms).empty());
  EXPECT_EQ(host.readField(table::kGoalVelocity, 3), 7u);
  EXPECT_EQ(host.readField(table::kModelNumber, 3), 1020u);
}

TEST(DynamixelEmulator, ReadsThePresentPosition) {
  EmulatorOptions options = optionsWithLink();
  options.initial_position = -1234;
  ServoEmulator servo(options);
  HostPort host(servo.port());
  EXPECT_EQ(static_cast<std::int32_t>(host.readField(table::kPresentPosition)), -1234);
  EXPECT_EQ(host.readField(table::kOperatingMode), 3u);  // position mode until the host sets 1
  EXPECT_EQ(host.readField(table::kVelocityLimit), 265u);
  EXPECT_EQ(host.readField(table::kReturnDelayTime), 0u);
  // The manual's READ example: 4 bytes at 132, answered with the 4 bytes.
  const Packet status = host.request(Packet{1, instruction::kRead, {0x84, 0x00, 0x04, 0x00}});
  EXPECT_EQ(status.params.size(), 5u);
}

TEST(DynamixelEmulator, RefusesEepromWritesWithTheTorqueOn) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  ASSERT_EQ(host.writeField(table::kTorqueEnable, 1), 0);
  EXPECT_EQ(host.writeField(table::kOperatingMode, kVelocityControlMode), 7);  // access error
  EXPECT_EQ(host.readField(table::kOperatingMode), 3u);
  ASSERT_EQ(host.writeField(table::kTorqueEnable, 0), 0);
  EXPECT_EQ(host.writeField(table::kOperatingMode, kVelocityControlMode), 0);
  EXPECT_EQ(host.readField(table::kOperatingMode), kVelocityControlMode);
}

TEST(DynamixelEmulator, RefusesReadOnlyFieldsPartialFieldsAndUnknownInstructions) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  EXPECT_EQ(host.writeField(table::kPresentPosition, 5), 7);
  EXPECT_EQ(host.writeField(table::kHardwareErrorStatus, 0), 7);
  EXPECT_EQ(host.writeField(table::kModelNumber, 1), 7);
  EXPECT_EQ(host.writeField(Field{104, 2}, 5), 5);            // half of Goal Velocity: data length error
  EXPECT_EQ(host.writeField(table::kOperatingMode, 2), 4);    // no such mode: data range error
  EXPECT_EQ(host.request(Packet{1, 0x7F, {}}).params[0], 2);  // instruction error
}

TEST(DynamixelEmulator, RefusesAGoalBeyondTheVelocityLimit) {
  EmulatorOptions options = optionsWithLink();
  options.velocity_limit = 100;
  ServoEmulator servo(options);
  HostPort host(servo.port());
  EXPECT_EQ(host.writeField(table::kGoalVelocity, 101), 6);  // data limit error
  EXPECT_EQ(host.writeField(table::kGoalVelocity, static_cast<std::uint32_t>(-101)), 6);
  EXPECT_EQ(host.readField(table::kGoalVelocity), 0u);  // not written
  EXPECT_EQ(host.writeField(table::kGoalVelocity, static_cast<std::uint32_t>(-100)), 0);
  EXPECT_EQ(static_cast<std::int32_t>(host.readField(table::kGoalVelocity)), -100);
}

TEST(DynamixelEmulator, TracksTheGoalVelocityAndCoastsToAStopWithTheTorqueOff) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  ASSERT_EQ(host.writeField(table::kGoalVelocity, 100), 0);
  EXPECT_EQ(host.readField(table::kPresentVelocity), 0u);  // torque off: the goal does nothing yet
  startVelocityControl(host);
  // 100 units = 2.4 rad/s, reached within 0.05 s at 50 rad/s^2.
  EXPECT_TRUE(eventually([&] { return host.readField(table::kPresentVelocity) == 100u; }));
  EXPECT_NEAR(servo.goalVelocity(), 2.398, 0.001);            // 100 x 0.229 rev/min
  EXPECT_NEAR(servo.velocity(), servo.goalVelocity(), 0.03);  // within about a unit of rounding
  EXPECT_EQ(host.readField(kMoving), 1u);
  const auto first = static_cast<std::int32_t>(host.readField(table::kPresentPosition));
  EXPECT_TRUE(eventually([&] { return static_cast<std::int32_t>(host.readField(table::kPresentPosition)) > first; }));

  ASSERT_EQ(host.writeField(table::kTorqueEnable, 0), 0);
  EXPECT_TRUE(eventually([&] { return host.readField(table::kPresentVelocity) == 0u; }));
  EXPECT_TRUE(eventually([&] { return servo.velocity() == 0.0; }));
  EXPECT_EQ(host.readField(kMoving), 0u);
  const std::uint32_t stopped = host.readField(table::kPresentPosition);
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(host.readField(table::kPresentPosition), stopped);
}

TEST(DynamixelEmulator, WrapsThePresentPositionAtInt32) {
  EmulatorOptions options = optionsWithLink();
  options.initial_position = std::numeric_limits<std::int32_t>::max() - 300;
  ServoEmulator servo(options);
  HostPort host(servo.port());
  startVelocityControl(host);
  ASSERT_EQ(host.writeField(table::kGoalVelocity, 200), 0);  // ~3100 counts/s
  std::int32_t present = 0;
  EXPECT_TRUE(eventually([&] {
    present = static_cast<std::int32_t>(host.readField(table::kPresentPosition));
    return present < 0;
  }));
  // Just past the wrap, as the real servo's two's complement counter; the true position went on.
  EXPECT_LT(present, std::numeric_limits<std::int32_t>::min() + 100000);
  EXPECT_GT(servo.position(), radians(*modelByName(options.model), std::numeric_limits<std::int32_t>::max()));
}

TEST(DynamixelEmulator, BusWatchdogStopsTheMotorUntilItIsReset) {
  ServoEmulator servo(optionsWithLink());
  HostPort host(servo.port());
  startVelocityControl(host);
  ASSERT_EQ(host.writeField(table::kGoalVelocity, 100), 0);
  ASSERT_EQ(host.writeField(table::kBusWatchdog, 5), 0);             // 100 ms of silence
  EXPECT_TRUE(eventually([&] { return servo.watchdogTripped(); }));  // the host says nothing meanwhile
  EXPECT_EQ(servo.goalVelocity(), 0.0);
  EXPECT_EQ(host.readField(table::kBusWatchdog), 0xFFu);
  EXPECT_TRUE(servo.torqueEnabled());
  EXPECT_TRUE(eventually([&] { return servo.velocity() == 0.0; }));  // ramped down
  EXPECT_EQ(host.writeField(table::kGoalVelocity, 100), 4);          // data range error while tripped
  EXPECT_EQ(host.writeField(table::kBusWatchdog, 5), 4);             // only 0 clears it
  ASSERT_EQ(host.writeField(table::kBusWatchdog, 0), 0);
  EXPECT_FALSE(servo.watchdogTripped());
  EXPECT_EQ(host.writeField(table::kGoalVelocity, 100), 0);
  EXPECT_TRUE(eventually([&] { return host.readField(table::kPresentVelocity) == 100u; }));
}

}  // namespace
}  // namespace uampc::dynamixel::test
