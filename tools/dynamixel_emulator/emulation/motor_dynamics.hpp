// The emulated motor: its velocity ramps toward a target at a constant acceleration (the motor's
// own dynamics, not the servo's Profile Acceleration) and its position is the exact integral of
// that piecewise-linear velocity, so that a test can predict it to the count.
#pragma once

namespace uampc::dynamixel::emulation {

struct MotorDynamics {
  double velocity = 0.0;  // rad/s
  double position = 0.0;  // rad, multi-turn

  // `seconds` later, having ramped toward `target_velocity` at `acceleration` (> 0) rad/s^2.
  void advance(double seconds, double target_velocity, double acceleration);
};

}  // namespace uampc::dynamixel::emulation
