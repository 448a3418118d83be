// One X-series servo without the wire: its control table, the instructions it executes, the
// replies it owes and the motor behind it. Time is passed in, so that it advances exactly; not
// thread-safe (ServoEmulator locks around it).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>

#include "control_table_image.hpp"
#include "emulator_options.hpp"
#include "motor_dynamics.hpp"
#include "uampc/dynamixel/protocol.hpp"

namespace uampc::dynamixel::emulation {

class EmulatedServo {
 public:
  using Clock = std::chrono::steady_clock;

  // Powered on at `now`; throws std::runtime_error for an unknown model or an impossible option.
  EmulatedServo(const EmulatorOptions& options, Clock::time_point now);

  // The motor, the bus watchdog and the Present fields brought to `now`.
  void advanceTo(Clock::time_point now);
  bool listensTo(std::uint8_t id) const;  // its ID or broadcast
  // Executes an instruction addressed to it (advanceTo(now) first); the status packet it owes.
  std::optional<Packet> execute(const Packet& instruction, Clock::time_point now);
  std::optional<Packet> crcErrorReply() const;  // for an instruction that arrived corrupted
  void raiseHardwareError(std::uint8_t bits);
  // A power cycle (REBOOT, or the adapter replugged): RAM at its power-on values, motor stopped,
  // position within one turn; EEPROM (ID, mode, limits) kept.
  void powerCycle(Clock::time_point now);
  std::chrono::microseconds returnDelay() const;  // Return Delay Time, 2 us units

  double velocity() const { return motor_.velocity; }
  double position() const { return motor_.position; }
  double goalVelocity() const;
  bool torqueEnabled() const;
  bool watchdogTripped() const;

 private:
  Packet status(std::uint8_t error, const std::vector<std::uint8_t>& data = {}) const;
  Packet ping() const;
  Packet read(const std::vector<std::uint8_t>& params) const;
  Packet write(const std::vector<std::uint8_t>& params);
  Packet reboot(Clock::time_point now);
  bool owesReply(const Packet& instruction) const;

  std::optional<Clock::time_point> watchdogDeadline() const;
  void integrateTo(Clock::time_point time);
  double targetVelocity() const;
  void publishPresent(Clock::time_point now);

  const Model& model_;
  double max_acceleration_;
  ControlTableImage table_;
  MotorDynamics motor_;
  Clock::time_point power_on_;
  Clock::time_point last_update_;
  Clock::time_point last_packet_;  // the bus watchdog's last communication
};

}  // namespace uampc::dynamixel::emulation
