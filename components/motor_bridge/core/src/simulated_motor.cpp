#include "uampc/motor/simulated_motor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace uampc::motor {

SimulatedMotor::SimulatedMotor(const MotorLimits& limits, double theta0, double omega0)
    : limits_(limits), theta_(theta0), omega_(std::clamp(omega0, -limits.max_speed, limits.max_speed)) {}

double SimulatedMotor::command(double omega_cmd) {
  omega_cmd_ = std::clamp(omega_cmd, -limits_.max_speed, limits_.max_speed);
  return omega_cmd_;
}

double SimulatedMotor::encoderTheta() const {
  if (limits_.encoder_resolution <= 0) return theta_;
  return std::round(theta_ / limits_.encoder_resolution) * limits_.encoder_resolution;
}

void SimulatedMotor::ramp(double t, double direction) {
  const double a = direction * limits_.max_acceleration;
  theta_ += omega_ * t + 0.5 * a * t * t;
  omega_ += a * t;
}

void SimulatedMotor::advance(double dt) {
  if (!(dt > 0)) return;
  const double tau = limits_.time_constant;
  const double a = limits_.max_acceleration;
  double remaining = dt;
  const double error = omega_cmd_ - omega_;
  const double direction = error >= 0 ? 1.0 : -1.0;
  // Phase 1: the lag would accelerate faster than the limit (|error| / tau > a): a linear ramp
  // until |error| = a * tau (or, without lag, until the command is reached).
  const double ramp_until = tau > 0 ? a * tau : 0.0;
  if (std::abs(error) > ramp_until) {
    const double t_ramp = (std::abs(error) - ramp_until) / a;
    if (t_ramp >= remaining) {
      ramp(remaining, direction);
      return;
    }
    ramp(t_ramp, direction);
    remaining -= t_ramp;
  }
  if (tau <= 0) {
    omega_ = omega_cmd_;
    theta_ += omega_ * remaining;
    return;
  }
  // Phase 2: the exponential approach, omega(t) = cmd - e0 exp(-t/tau), integrated exactly.
  const double e0 = omega_cmd_ - omega_;
  const double decay = std::exp(-remaining / tau);
  theta_ += omega_cmd_ * remaining - e0 * tau * (1.0 - decay);
  omega_ = omega_cmd_ - e0 * decay;
}

}  // namespace uampc::motor
