#include "dynamixel_backend.hpp"

#include <cmath>

#include "uampc/dynamixel/control_table.hpp"

namespace uampc {

DynamixelBackend::DynamixelBackend(const DynamixelBackendOptions& options, const Logger& log)
    : options_(options), log_(log), servo_(std::make_unique<dynamixel::Servo>(options.servo)) {
  log_.info("DYNAMIXEL ", servo_->model().name, " ", servo_->where(), " in velocity mode; velocity limit ",
            servo_->velocityLimit(), " rad/s");
}

DynamixelBackend::~DynamixelBackend() {
  servo_->release();  // torque off: a stopped bridge leaves the motor coasting, not driven
  const auto& c = servo_->bus().counters();
  log_.info("DYNAMIXEL bus: ", c.transactions, " transactions, ", c.timeouts, " timeouts, ", c.corrupt,
            " corrupt replies, ", c.stale, " late replies skipped, ", c.port_errors, " port errors, ", c.bytes_sent,
            " bytes sent, ", c.bytes_received, " received; ", faults_, " time(s) lost");
}

void DynamixelBackend::command(double omega, Time now) {
  if (lost_) return;  // applied when the servo is back and the next command comes
  try {
    const double applied = servo_->setVelocity(omega);
    if (std::abs(applied - omega) > servo_->velocityLimit() * 1e-3 + 0.01) {
      clamp_log_.warn(log_, "command ", omega, " rad/s exceeds the servo's velocity limit ", servo_->velocityLimit(),
                      " rad/s (Velocity Limit, address 44); clamping (said once)");
    }
  } catch (const dynamixel::BusFault& e) {
    lose(e.what(), now);
  }
}

std::optional<MotorReading> DynamixelBackend::read(Time now) {
  if (lost_) {
    tryReconnect(now);
    if (lost_) return std::nullopt;
  }
  // `now` is the scene's time at this call; the servo samples its encoder a little later (half the
  // round trip, more after a retry). Measured on the steady clock from the same instant.
  const auto called = dynamixel::SteadyClock::now();
  try {
    const dynamixel::ServoState state = servo_->readState();
    reportHardwareError(state.hardware_error);
    const double after_call = std::chrono::duration<double>(state.stamp - called).count();
    return MotorReading{state.position, state.velocity, now + Time::fromSeconds(after_call)};
  } catch (const dynamixel::BusFault& e) {
    lose(e.what(), now);
    return std::nullopt;
  }
}

void DynamixelBackend::lose(const std::string& why, Time now) {
  lost_ = true;
  ++faults_;
  lost_since_ = now;
  next_reconnect_ = now;
  log_.error("DYNAMIXEL bus lost: ", why, "; no encoder state is published until it answers again (the servo's",
             " bus watchdog stops the motor meanwhile); reconnecting every ", options_.reconnect_interval_s, " s");
}

void DynamixelBackend::tryReconnect(Time now) {
  if (now < next_reconnect_) return;
  next_reconnect_ = now + Time::fromSeconds(options_.reconnect_interval_s);
  try {
    servo_->reconnect();
    servo_->setVelocity(options_.fault_speed);
  } catch (const std::exception&) {
    return;  // still away; said once when it was lost
  }
  lost_ = false;
  log_.info("DYNAMIXEL ", servo_->where(), " answers again after ", (now - lost_since_).seconds(), " s; driving at ",
            options_.fault_speed, " rad/s until the next command");
}

void DynamixelBackend::reportHardwareError(std::uint8_t status) {
  if (status == hardware_error_) return;
  hardware_error_ = status;
  if (status == 0) {
    log_.info("DYNAMIXEL ", servo_->where(), ": hardware error cleared");
    return;
  }
  log_.error("DYNAMIXEL ", servo_->where(), " reports a hardware error: ", dynamixel::hardwareErrorText(status),
             "; the servo has turned its torque off. Remove the cause, then power-cycle or reboot it");
}

}  // namespace uampc
