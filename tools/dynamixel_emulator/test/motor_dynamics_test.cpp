// The motor's ramp and its exact integral, without the wire: numbers a host could predict.
#include <gtest/gtest.h>

#include "emulation/motor_dynamics.hpp"

namespace uampc::dynamixel::emulation {
namespace {

TEST(DynamixelEmulatorMotor, IntegratesTheRampExactly) {
  MotorDynamics motor;
  motor.advance(0.1, 10.0, 50.0);  // still ramping: 5 rad/s, 0.25 rad
  EXPECT_DOUBLE_EQ(motor.velocity, 5.0);
  EXPECT_DOUBLE_EQ(motor.position, 0.25);
  motor.advance(0.9, 10.0, 50.0);  // reaches 10 rad/s at 0.2 s: 0.75 rad more, then 8 rad
  EXPECT_DOUBLE_EQ(motor.velocity, 10.0);
  EXPECT_DOUBLE_EQ(motor.position, 9.0);
}

TEST(DynamixelEmulatorMotor, RampsDownAndReversesAtTheSameRate) {
  MotorDynamics motor{10.0, 0.0};
  motor.advance(1.0, -10.0, 50.0);  // 0.4 s to -10 rad/s through 0, crossing area cancels
  EXPECT_DOUBLE_EQ(motor.velocity, -10.0);
  EXPECT_NEAR(motor.position, -6.0, 1e-12);
  motor.advance(0.0, 0.0, 50.0);  // no time, no change
  EXPECT_DOUBLE_EQ(motor.velocity, -10.0);
}

}  // namespace
}  // namespace uampc::dynamixel::emulation
