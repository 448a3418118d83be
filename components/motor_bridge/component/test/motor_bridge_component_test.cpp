// The adapter in-process: encoder states at the encoder rate, following the commands, within the
// limits, and the safe speed when commands stop.
#include <gtest/gtest.h>

#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

// An ideal motor (no lag, practically no acceleration limit, exact encoder), so that the
// published states can be predicted exactly.
const std::map<std::string, std::string> kIdealMotor = {
    {"encoder_rate", "100"}, {"time_constant", "0"}, {"max_acceleration", "1e6"}, {"encoder_resolution", "0"}};

msg::MotorCommand command(double velocity) {
  msg::MotorCommand c;
  c.velocity(velocity);
  return c;
}

std::map<std::string, std::string> with(std::map<std::string, std::string> params,
                                        const std::map<std::string, std::string>& more) {
  for (const auto& [k, v] : more) params[k] = v;
  return params;
}

TEST(MotorBridgeComponent, PublishesStatesAtTheEncoderRateFollowingTheCommand) {
  testing::TestContext ctx("motor_bridge", kIdealMotor);
  ctx.advanceTo(Time{0});
  ctx.inject("command", command(5.0));
  ctx.advanceTo(Time::fromSeconds(0.2));
  const auto states = ctx.published<sensor_msgs::msg::JointState>("state");
  ASSERT_EQ(states.size(), 21u);            // 0, 0.01, ..., 0.2 s
  EXPECT_EQ(states[0].velocity()[0], 0.0);  // at rest before the command
  for (std::size_t i = 0; i < states.size(); ++i) {
    EXPECT_EQ(fromMsg(states[i].header().stamp()), Time::fromSeconds(0.01 * static_cast<double>(i)));
    EXPECT_EQ(states[i].name(), std::vector<std::string>{"motor"});
  }
  EXPECT_NEAR(states.back().velocity()[0], 5.0, 1e-9);
  EXPECT_NEAR(states.back().position()[0], 1.0, 1e-3);  // 5 rad/s for 0.2 s
}

TEST(MotorBridgeComponent, ClampsCommandsBeyondMaxSpeed) {
  testing::TestContext ctx("motor_bridge", with(kIdealMotor, {{"max_speed", "8"}}));
  ctx.advanceTo(Time{0});
  ctx.inject("command", command(-50.0));
  ctx.advanceTo(Time::fromSeconds(0.1));
  EXPECT_NEAR(ctx.published<sensor_msgs::msg::JointState>("state").back().velocity()[0], -8.0, 1e-9);
}

TEST(MotorBridgeComponent, FallsBackToTheSafeSpeedWhenCommandsStop) {
  testing::TestContext ctx("motor_bridge", with(kIdealMotor, {{"command_timeout", "0.2"}, {"safe_speed", "1.5"}}));
  ctx.advanceTo(Time{0});
  ctx.inject("command", command(6.0));
  ctx.advanceTo(Time::fromSeconds(0.15));
  EXPECT_NEAR(ctx.published<sensor_msgs::msg::JointState>("state").back().velocity()[0], 6.0, 1e-9);
  ctx.advanceTo(Time::fromSeconds(0.4));
  EXPECT_NEAR(ctx.published<sensor_msgs::msg::JointState>("state").back().velocity()[0], 1.5, 1e-9);
  // A non-finite command is ignored: the fallback holds.
  ctx.inject("command", command(std::nan("")));
  ctx.advanceTo(Time::fromSeconds(0.5));
  EXPECT_NEAR(ctx.published<sensor_msgs::msg::JointState>("state").back().velocity()[0], 1.5, 1e-9);
}

}  // namespace
}  // namespace uampc
