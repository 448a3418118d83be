// backend: sim, the simulated motor of uampc_motor_core, advanced on the scene's clock.
#pragma once

#include "motor_backend.hpp"
#include "uampc/motor/simulated_motor.hpp"

namespace uampc {

class SimBackend : public MotorBackend {
 public:
  SimBackend(const motor::MotorLimits& limits, double initial_angle, Time now)
      : motor_(limits, initial_angle), last_update_(now) {
    motor_.command(0.0);  // at rest until the first command
  }

  void command(double omega, Time now) override {
    advanceTo(now);
    motor_.command(omega);
  }

  std::optional<MotorReading> read(Time now) override {
    advanceTo(now);
    return MotorReading{motor_.encoderTheta(), motor_.omega(), now};
  }

 private:
  // Brings the motor to the present under the command it had so far.
  void advanceTo(Time now) {
    motor_.advance((now - last_update_).seconds());
    last_update_ = now;
  }

  motor::SimulatedMotor motor_;
  Time last_update_;
};

}  // namespace uampc
