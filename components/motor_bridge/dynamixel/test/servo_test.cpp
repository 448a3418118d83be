// The servo layer against an emulated XM430 on a pseudo-terminal (tools/dynamixel_emulator): the
// real serial port, the real protocol, every fault of a real bus injected by the emulator.
#include <gtest/gtest.h>

#include <unistd.h>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "servo_emulator.hpp"
#include "uampc/dynamixel/servo.hpp"

namespace uampc::dynamixel {
namespace {

using std::chrono::milliseconds;

std::string linkPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("uampc_dxl_" + name + "_" + std::to_string(getpid()))).string();
}

EmulatorOptions emulated(const std::string& name) {
  EmulatorOptions o;
  o.link = linkPath(name);
  o.id = 1;
  o.model = "XM430-W350";
  o.velocity_limit = 265;  // 6.35 rad/s
  o.max_acceleration = 50.0;
  return o;
}

ServoOptions servoOn(const ServoEmulator& emulator) {
  ServoOptions o;
  o.port = emulator.port();
  o.id = 1;
  o.model = "XM430-W350";
  // The emulator's thread shares two cores with the other tests: a reply can be tens of ms late.
  o.reply_timeout_s = 0.1;
  o.max_retries = 2;
  o.bus_watchdog_s = 0.3;
  return o;
}

// Reads at 100 Hz for `duration`, as the bridge's encoder timer does (and as the bus watchdog wants).
ServoState readFor(Servo& servo, std::chrono::milliseconds duration) {
  const auto end = SteadyClock::now() + duration;
  ServoState state = servo.readState();
  while (SteadyClock::now() < end) {
    std::this_thread::sleep_for(milliseconds(10));
    state = servo.readState();
  }
  return state;
}

// True when a read succeeds within `tries` attempts (each already retried): on a loaded machine the
// emulator may miss one.
bool answersWithin(Servo& servo, int tries) {
  for (int i = 0; i < tries; ++i) {
    try {
      servo.readState();
      return true;
    } catch (const BusFault&) {
    }
  }
  return false;
}

double seconds(SteadyClock::duration d) { return std::chrono::duration<double>(d).count(); }

TEST(DynamixelServo, SetsUpVelocityModeAndTracksTheCommand) {
  ServoEmulator emulator(emulated("track"));
  Servo servo(servoOn(emulator));
  EXPECT_TRUE(emulator.torqueEnabled());
  EXPECT_NEAR(servo.velocityLimit(), radiansPerSecond(*modelByName("XM430-W350"), 265), 1e-9);
  const double applied = servo.setVelocity(3.0);
  EXPECT_NEAR(applied, 3.0, 0.024);                             // one velocity unit is 0.024 rad/s
  const ServoState before = readFor(servo, milliseconds(300));  // 3 rad/s at 50 rad/s^2: 60 ms of ramp
  EXPECT_NEAR(before.velocity, applied, 0.03);
  const ServoState after = readFor(servo, milliseconds(500));
  const double travelled = after.position - before.position;
  EXPECT_NEAR(travelled / seconds(after.stamp - before.stamp), applied, 0.1);
  EXPECT_NEAR(after.position, emulator.position(), 0.1);  // the emulator keeps turning after the read
  EXPECT_GT(after.round_trip_s, 0.0);
}

TEST(DynamixelServo, ClampsCommandsToTheServosVelocityLimit) {
  ServoEmulator emulator(emulated("clamp"));
  Servo servo(servoOn(emulator));
  EXPECT_NEAR(servo.setVelocity(100.0), servo.velocityLimit(), 1e-9);
  EXPECT_NEAR(servo.setVelocity(-100.0), -servo.velocityLimit(), 1e-9);
  EXPECT_NEAR(emulator.goalVelocity(), -servo.velocityLimit(), 1e-6);
}

TEST(DynamixelServo, UnwrapsThePositionAcrossTheInt32Wrap) {
  EmulatorOptions o = emulated("wrap");
  o.initial_position = 2147483647 - 2000;  // half a turn before Present Position wraps to -2^31
  ServoEmulator emulator(o);
  Servo servo(servoOn(emulator));
  const ServoState start = servo.readState();
  const double true_start = emulator.position();
  servo.setVelocity(-6.0);  // away from the wrap first, then...
  readFor(servo, milliseconds(200));
  servo.setVelocity(6.0);  // ...through it: 6 rad/s for 1.5 s is 1.4 turns
  const ServoState end = readFor(servo, milliseconds(1500));
  const double true_travel = emulator.position() - true_start;
  EXPECT_GT(true_travel, 4.0);  // it did pass the wrap (2000 counts = 3.07 rad)
  EXPECT_NEAR(end.position - start.position, true_travel, 0.1);
}

TEST(DynamixelServo, NamesThePortAndIdWhenNothingAnswers) {
  ServoEmulator emulator(emulated("noid"));
  ServoOptions o = servoOn(emulator);
  o.id = 7;
  try {
    Servo servo(o);
    FAIL() << "a servo without an answer at ID 7";
  } catch (const BusFault& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no DYNAMIXEL answered as ID 7 on " + emulator.port() + " at 1000000 baud"), std::string::npos)
        << what;
  }
  o.port = linkPath("missing");
  try {
    Servo servo(o);
    FAIL() << "a port that does not exist";
  } catch (const SerialError& e) {
    EXPECT_NE(std::string(e.what()).find("serial port " + o.port + ": cannot open"), std::string::npos) << e.what();
  }
}

TEST(DynamixelServo, RefusesAnotherModelNamingBoth) {
  EmulatorOptions eo = emulated("model");
  eo.model = "XL430-W250";
  ServoEmulator emulator(eo);
  try {
    Servo servo(servoOn(emulator));
    FAIL() << "an XL430 taken for an XM430";
  } catch (const BusFault& e) {
    EXPECT_NE(std::string(e.what()).find("is model 1060 (XL430-W250), the scene says XM430-W350"), std::string::npos)
        << e.what();
  }
}

TEST(DynamixelServo, RetriesACorruptReplyAndGivesUpAfterItsTries) {
  ServoEmulator emulator(emulated("crc"));
  Servo servo(servoOn(emulator));
  emulator.corruptReplies(1);
  EXPECT_NO_THROW(servo.readState());
  EXPECT_EQ(servo.bus().counters().corrupt, 1u);
  emulator.corruptReplies(3);  // 1 + max_retries
  EXPECT_THROW(servo.readState(), BusFault);
  EXPECT_EQ(servo.bus().counters().corrupt, 4u);
  EXPECT_NO_THROW(servo.readState());  // and the bus works again
}

TEST(DynamixelServo, ASilentServoIsAFaultWithinItsTimeouts) {
  ServoEmulator emulator(emulated("silent"));
  ServoOptions options = servoOn(emulator);
  options.reply_timeout_s = 0.02;  // a real bus answers in microseconds (dynamixel_bench times it)
  options.bus_watchdog_s = 0;
  Servo servo(options);
  emulator.setSilent(true);
  try {
    servo.readState();
    FAIL() << "a silent servo read";
  } catch (const BusFault& e) {
    EXPECT_NE(std::string(e.what()).find("failed after 3 tries: no status packet within 20000 us"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(servo.bus().counters().timeouts, 3u);
  emulator.setSilent(false);
  EXPECT_TRUE(answersWithin(servo, 10));
}

TEST(DynamixelServo, ReportsAHardwareError) {
  ServoEmulator emulator(emulated("hwerror"));
  Servo servo(servoOn(emulator));
  servo.setVelocity(2.0);
  EXPECT_EQ(readFor(servo, milliseconds(50)).hardware_error, 0);
  emulator.setHardwareError(0x20);  // overload
  const ServoState state = servo.readState();
  EXPECT_EQ(state.hardware_error, 0x20);
  EXPECT_EQ(hardwareErrorText(state.hardware_error), "overload");
  EXPECT_FALSE(emulator.torqueEnabled());
}

TEST(DynamixelServo, ClearsATrippedBusWatchdogOnTheNextCommand) {
  ServoEmulator emulator(emulated("watchdog"));
  Servo servo(servoOn(emulator));
  servo.setVelocity(3.0);
  readFor(servo, milliseconds(200));
  std::this_thread::sleep_for(milliseconds(800));  // the host falls silent: the 0.3 s watchdog trips
  EXPECT_TRUE(emulator.watchdogTripped());
  EXPECT_NEAR(emulator.goalVelocity(), 0.0, 1e-9);
  servo.setVelocity(3.0);
  EXPECT_FALSE(emulator.watchdogTripped());
  EXPECT_NEAR(emulator.goalVelocity(), 3.0, 0.03);
}

TEST(DynamixelServo, AnUnpluggedBusFailsAtOnceAndReconnectsWhenItIsBack) {
  ServoEmulator emulator(emulated("unplug"));
  Servo servo(servoOn(emulator));
  servo.setVelocity(4.0);
  const ServoState before = readFor(servo, milliseconds(300));
  emulator.unplug();
  EXPECT_THROW(servo.readState(), BusFault);
  EXPECT_THROW(servo.reconnect(), std::exception);
  emulator.replug();  // a power cycle too: torque off, the count restarts within one turn
  ASSERT_NO_THROW(servo.reconnect());
  EXPECT_TRUE(emulator.torqueEnabled());
  const ServoState after = servo.readState();
  // The angle goes on from where it was, within half a turn (whole turns while away are unknown).
  EXPECT_LE(std::abs(after.position - before.position), M_PI + 0.01);
  EXPECT_GE(servo.bus().counters().port_errors, 1u);
}

TEST(DynamixelServo, BusBudgetOfAnEncoderReadAndACommand) {
  ServoEmulator emulator(emulated("budget"));
  Servo servo(servoOn(emulator));
  const BusCounters start = servo.bus().counters();
  servo.readState();
  const BusCounters read = servo.bus().counters();
  servo.setVelocity(1.0);
  const BusCounters command = servo.bus().counters();
  // Request 14 bytes + status 19 bytes; request 16 + status 11 (Protocol 2.0 framing).
  EXPECT_EQ(read.bytes_sent - start.bytes_sent, 14u);
  EXPECT_EQ(read.bytes_received - start.bytes_received, 19u);
  EXPECT_EQ(command.bytes_sent - read.bytes_sent, 16u);
  EXPECT_EQ(command.bytes_received - read.bytes_received, 11u);
}

}  // namespace
}  // namespace uampc::dynamixel
