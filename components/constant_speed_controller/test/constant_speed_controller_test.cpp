// The adapter in-process: one command per period, at the configured speed.
#include <gtest/gtest.h>

#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

TEST(ConstantSpeedControllerComponent, CommandsItsSpeedEveryPeriodFromTheStart) {
  testing::TestContext ctx("constant_speed_controller", {{"speed", "-1.25"}, {"rate", "5"}});
  ctx.advanceTo(Time::fromSeconds(1.0));
  const auto commands = ctx.published<msg::MotorCommand>("command");
  ASSERT_EQ(commands.size(), 6u);  // 0, 0.2, ..., 1.0 s
  for (std::size_t i = 0; i < commands.size(); ++i) {
    EXPECT_EQ(commands[i].velocity(), -1.25);
    EXPECT_EQ(fromMsg(commands[i].header().stamp()), Time::fromSeconds(0.2 * static_cast<double>(i)));
  }
}

TEST(ConstantSpeedControllerComponent, StepsThroughItsSpeedsEachForItsPeriod) {
  testing::TestContext ctx("constant_speed_controller",
                           {{"speeds", "[2.0, 5.0, -1.0]"}, {"speed_period", "0.5"}, {"rate", "5"}});
  ctx.advanceTo(Time::fromSeconds(1.6));
  const auto commands = ctx.published<msg::MotorCommand>("command");
  ASSERT_EQ(commands.size(), 9u);  // 0, 0.2, ..., 1.6 s
  const double expected[] = {2.0, 2.0, 2.0, 5.0, 5.0, -1.0, -1.0, -1.0, 2.0};
  for (std::size_t i = 0; i < commands.size(); ++i) EXPECT_EQ(commands[i].velocity(), expected[i]) << i;
}

}  // namespace
}  // namespace uampc
