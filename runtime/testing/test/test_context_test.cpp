// The test context itself, on the two smallest components.
#include <gtest/gtest.h>

#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/std_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc::testing {
namespace {

std::vector<double> stampsOf(const std::vector<msg::MotorCommand>& commands) {
  std::vector<double> stamps;
  for (const auto& c : commands) stamps.push_back(fromMsg(c.header().stamp()).seconds());
  return stamps;
}

TEST(TestContext, FillsDefaultsFromDescribeAndReadsGivenValues) {
  TestContext ctx("constant_speed_controller", {{"speed", "2.5"}});
  EXPECT_EQ(ctx.paramDouble("speed"), 2.5);
  EXPECT_EQ(ctx.paramDouble("rate"), 10.0);  // describe()'s default
}

TEST(TestContext, RejectsParametersAsASceneWould) {
  EXPECT_THROW(TestContext("constant_speed_controller", {{"sped", "1"}}), std::invalid_argument);
  EXPECT_THROW(TestContext("constant_speed_controller", {{"speed", "fast"}}), std::invalid_argument);
  EXPECT_THROW(TestContext("constant_speed_controller", {{"speed", "2000"}}), std::invalid_argument);
  EXPECT_THROW(TestContext("motor_bridge", {{"backend", "serial"}}), std::invalid_argument);
  EXPECT_THROW(TestContext("no_such_component"), std::invalid_argument);
  try {
    TestContext("constant_speed_controller", {{"rate", "0"}});
    FAIL() << "rate 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'rate'"), std::string::npos) << e.what();
  }
}

TEST(TestContext, TimersFireAtTheirOwnTimesInOrder) {
  TestContext ctx("constant_speed_controller", {{"rate", "4"}});
  EXPECT_EQ(ctx.publishedCount("command"), 0u);  // nothing before the clock starts
  ctx.advanceTo(Time::fromSeconds(0.6));
  EXPECT_EQ(stampsOf(ctx.published<msg::MotorCommand>("command")), (std::vector<double>{0.0, 0.25, 0.5}));
  EXPECT_EQ(ctx.now(), Time::fromSeconds(0.6));
  ctx.advanceBy(0.15);
  EXPECT_EQ(ctx.publishedCount("command"), 4u);
  EXPECT_THROW(ctx.advanceTo(Time::fromSeconds(0.1)), std::invalid_argument);
}

TEST(TestContext, ATimerFiresOncePerPeriodFromTimeZero) {
  TestContext ctx("motor_bridge", {{"encoder_rate", "100"}});
  ctx.advanceTo(Time::fromSeconds(0.05));
  const auto states = ctx.published<sensor_msgs::msg::JointState>("state");
  ASSERT_EQ(states.size(), 6u);
  for (std::size_t i = 1; i < states.size(); ++i) {
    EXPECT_EQ(fromMsg(states[i].header().stamp()) - fromMsg(states[i - 1].header().stamp()), Time::fromSeconds(0.01));
  }
}

TEST(TestContext, PortsAreCheckedByNameDirectionAndType) {
  TestContext ctx("motor_bridge");
  EXPECT_THROW(ctx.inject("comand", msg::MotorCommand()), std::logic_error);
  EXPECT_THROW(ctx.inject("command", std_msgs::msg::Float64()), std::logic_error);
  EXPECT_THROW(ctx.inject("state", sensor_msgs::msg::JointState()), std::logic_error);  // an output
  EXPECT_THROW(ctx.published<msg::MotorCommand>("state"), std::logic_error);
  EXPECT_EQ(ctx.topicOf("state"), "/motor/state");
}

}  // namespace
}  // namespace uampc::testing
