#include "motor_dynamics.hpp"

#include <cmath>

namespace uampc::dynamixel::emulation {

void MotorDynamics::advance(double seconds, double target_velocity, double acceleration) {
  if (seconds <= 0.0) return;
  const double gap = target_velocity - velocity;
  const double time_to_target = std::abs(gap) / acceleration;
  if (time_to_target >= seconds) {  // still ramping at the end: a trapezoid
    const double end_velocity = velocity + std::copysign(acceleration * seconds, gap);
    position += (velocity + end_velocity) / 2.0 * seconds;
    velocity = end_velocity;
    return;
  }
  // The ramp's trapezoid, then the target velocity for the rest of the interval.
  position += (velocity + target_velocity) / 2.0 * time_to_target + target_velocity * (seconds - time_to_target);
  velocity = target_velocity;
}

}  // namespace uampc::dynamixel::emulation
