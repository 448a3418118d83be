// A simulated motor: speed and acceleration limits, first-order lag, encoder resolution.
//
// The speed follows the command as a first-order lag, d omega/dt = (omega_cmd - omega) / tau,
// with |d omega/dt| capped at the acceleration limit (tau = 0: a pure acceleration-limited ramp).
// Between two calls the command is constant, so omega(t) and theta(t) = integral of omega are
// integrated in closed form (a linear ramp, then an exponential): theta is exact at any time,
// whatever the call rate; the discrete model of the paper, theta_{i+1} = theta_i + omega_i dt,
// is its limit for tau = 0 and an unbounded acceleration.
#pragma once

namespace uampc::motor {

struct MotorLimits {
  double max_speed = 20.0;          // rad/s, |omega| and |omega_cmd| are clamped to it
  double max_acceleration = 100.0;  // rad/s^2
  double time_constant = 0.02;      // s, first-order lag tau; 0: none
  double encoder_resolution = 2.0 * 3.14159265358979323846 / 4096.0;  // rad per count (12-bit encoder)
};

class SimulatedMotor {
 public:
  explicit SimulatedMotor(const MotorLimits& limits, double theta0 = 0.0, double omega0 = 0.0);

  // The command from now on; clamped to the speed limit. Returns the value applied.
  double command(double omega_cmd);
  // Advances the motor by dt seconds under the current command.
  void advance(double dt);

  double theta() const { return theta_; }  // rad, exact, multi-turn
  double omega() const { return omega_; }  // rad/s
  double commanded() const { return omega_cmd_; }
  // What the encoder reads: theta rounded to the nearest count.
  double encoderTheta() const;

 private:
  void ramp(double t, double direction);

  MotorLimits limits_;
  double theta_;
  double omega_;
  double omega_cmd_ = 0.0;
};

}  // namespace uampc::motor
