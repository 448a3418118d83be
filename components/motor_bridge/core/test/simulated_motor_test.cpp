#include <gtest/gtest.h>

#include <cmath>

#include "uampc/motor/simulated_motor.hpp"

namespace uampc::motor {
namespace {

// Reference: the same ODE integrated with tiny explicit Euler steps.
struct EulerMotor {
  MotorLimits limits;
  double theta = 0, omega = 0, cmd = 0;
  void advance(double dt) {
    const double h = 1e-6;
    for (double t = 0; t < dt - 1e-12; t += h) {
      double accel = limits.time_constant > 0 ? (cmd - omega) / limits.time_constant
                                              : (cmd > omega ? 1e12 : (cmd < omega ? -1e12 : 0.0));
      accel = std::clamp(accel, -limits.max_acceleration, limits.max_acceleration);
      double next = omega + accel * h;
      if (limits.time_constant <= 0 && (next - cmd) * (omega - cmd) < 0) next = cmd;  // no overshoot
      theta += 0.5 * (omega + next) * h;
      omega = next;
    }
  }
};

class MotorAgainstEuler : public ::testing::TestWithParam<MotorLimits> {};

TEST_P(MotorAgainstEuler, ClosedFormMatchesFineIntegration) {
  SimulatedMotor motor(GetParam());
  EulerMotor reference{GetParam()};
  const double commands[] = {3.6, 3.6, -2.0, 10.0, 0.0, 7.2};
  for (double cmd : commands) {
    motor.command(cmd);
    reference.cmd = cmd;
    for (int i = 0; i < 20; ++i) {  // 20 x 5 ms per command
      motor.advance(0.005);
      reference.advance(0.005);
    }
    EXPECT_NEAR(motor.omega(), reference.omega, 1e-3);
    EXPECT_NEAR(motor.theta(), reference.theta, 1e-4);
  }
}

INSTANTIATE_TEST_SUITE_P(Limits, MotorAgainstEuler,
                         ::testing::Values(MotorLimits{20.0, 100.0, 0.02, 0.0},  // lag, ramp first
                                           MotorLimits{20.0, 1e4, 0.05, 0.0},    // lag only
                                           MotorLimits{20.0, 50.0, 0.0, 0.0}));  // ramp only

TEST(SimulatedMotor, ResultDoesNotDependOnTheCallRate) {
  MotorLimits limits;
  SimulatedMotor coarse(limits), fine(limits);
  coarse.command(5.0);
  fine.command(5.0);
  coarse.advance(0.3);
  for (int i = 0; i < 300; ++i) fine.advance(0.001);
  EXPECT_NEAR(coarse.theta(), fine.theta(), 1e-9);
  EXPECT_NEAR(coarse.omega(), fine.omega(), 1e-9);
}

TEST(SimulatedMotor, ClampsCommandToSpeedLimitAndRespectsAcceleration) {
  MotorLimits limits{5.0, 10.0, 0.0, 0.0};
  SimulatedMotor motor(limits);
  EXPECT_DOUBLE_EQ(motor.command(100.0), 5.0);
  motor.advance(0.1);
  EXPECT_NEAR(motor.omega(), 1.0, 1e-12);  // 10 rad/s^2 for 0.1 s
  EXPECT_NEAR(motor.theta(), 0.05, 1e-12);
  motor.advance(10.0);
  EXPECT_DOUBLE_EQ(motor.omega(), 5.0);
}

TEST(SimulatedMotor, WithoutLagOrLimitThetaIsTheIntegralOfTheCommand) {
  MotorLimits limits{20.0, 1e9, 0.0, 0.0};
  SimulatedMotor motor(limits);
  motor.command(3.6);
  for (int i = 0; i < 12000; ++i) motor.advance(0.005);
  EXPECT_NEAR(motor.theta(), 3.6 * 60.0, 1e-6);
}

TEST(SimulatedMotor, EncoderQuantisesToItsResolution) {
  MotorLimits limits{20.0, 1e9, 0.0, 0.01};
  SimulatedMotor motor(limits, 0.1234);
  EXPECT_NEAR(motor.encoderTheta(), 0.12, 1e-12);
  EXPECT_LE(std::abs(motor.encoderTheta() - motor.theta()), 0.005 + 1e-12);
}

}  // namespace
}  // namespace uampc::motor
