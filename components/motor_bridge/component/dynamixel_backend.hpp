// backend: dynamixel, an X-series servo on a serial bus (docs/user/rig.md), and what the bridge does
// when the bus fails:
//   - each operation is tried 1 + max_retries times, reply_timeout each, so one tick never blocks
//     for more than a few tens of milliseconds;
//   - when every try fails (timeouts, corrupt replies, the port gone) the bus is "lost": the bridge
//     says so, publishes no encoder state (none would be true), and reopens the port every
//     reconnect_interval. Meanwhile the servo's own bus watchdog stops the motor;
//   - when the servo answers again it is set up as at the start and driven at the on_fault speed
//     (safe_speed or 0) until the next command arrives;
//   - a hardware error (overload, overheating...) is named once; the servo has turned its torque off
//     itself, and the bridge keeps reading its encoder. Clearing it takes a person: power-cycle the
//     servo or reboot it (DYNAMIXEL Wizard) once the cause is gone.
#pragma once

#include <memory>
#include <string>

#include "motor_backend.hpp"
#include "uampc/dynamixel/servo.hpp"
#include "uampc/runtime/logger.hpp"

namespace uampc {

struct DynamixelBackendOptions {
  dynamixel::ServoOptions servo;
  double reconnect_interval_s = 0.5;
  double fault_speed = 0.0;  // rad/s after a reconnection, until the next command
};

class DynamixelBackend : public MotorBackend {
 public:
  // Throws with the port, baud rate and ID named when the servo cannot be reached or is not the
  // model the scene says.
  DynamixelBackend(const DynamixelBackendOptions& options, const Logger& log);
  ~DynamixelBackend() override;

  void command(double omega, Time now) override;
  std::optional<MotorReading> read(Time now) override;

 private:
  void lose(const std::string& why, Time now);
  void tryReconnect(Time now);
  void reportHardwareError(std::uint8_t status);

  DynamixelBackendOptions options_;
  const Logger& log_;
  std::unique_ptr<dynamixel::Servo> servo_;
  bool lost_ = false;
  Time lost_since_;
  Time next_reconnect_;
  long faults_ = 0;
  std::uint8_t hardware_error_ = 0;
  RateLimitedLog clamp_log_ = RateLimitedLog::once();
};

}  // namespace uampc
