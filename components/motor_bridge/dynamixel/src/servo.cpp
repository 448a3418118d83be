#include "uampc/dynamixel/servo.hpp"

#include <algorithm>
#include <cmath>

namespace uampc::dynamixel {
namespace {

Packet readRequest(std::uint8_t id, Field field) {
  Packet p{id, instruction::kRead, {}};
  appendLittleEndian(p.params, field.address, 2);
  appendLittleEndian(p.params, field.size, 2);
  return p;
}

Packet writeRequest(std::uint8_t id, Field field, std::uint32_t value) {
  Packet p{id, instruction::kWrite, {}};
  appendLittleEndian(p.params, field.address, 2);
  appendLittleEndian(p.params, value, field.size);
  return p;
}

constexpr std::uint8_t kDataRangeError = 4;
// Status parameters: the error byte, then the model number and firmware for a ping, nothing for a write.
constexpr std::size_t kPingStatusParams = 4;
constexpr std::size_t kWriteStatusParams = 1;

}  // namespace

Servo::Servo(const ServoOptions& options)
    : options_(options),
      bus_(options.port, options.baud_rate,
           std::chrono::microseconds(static_cast<std::int64_t>(options.reply_timeout_s * 1e6))) {
  identify();
  setUp();
}

std::string Servo::where() const {
  return "ID " + std::to_string(options_.id) + " on " + options_.port + " at " + std::to_string(options_.baud_rate) +
         " baud";
}

Reply Servo::request(const Packet& packet, std::size_t expected_params, const char* what) {
  Reply reply;
  int tries = 0;
  // A failed port is not retried: it stays failed until reopened.
  while (tries <= options_.max_retries) {
    ++tries;
    reply = bus_.transact(packet, expected_params);
    if (reply.ok() || reply.outcome == Reply::Outcome::kPortError) break;
  }
  if (!reply.ok()) {
    throw BusFault(std::string(what) + " of DYNAMIXEL " + where() + " failed after " + std::to_string(tries) +
                   (tries == 1 ? " try: " : " tries: ") + reply.detail);
  }
  return reply;
}

std::uint32_t Servo::read(Field field, const char* what) {
  const Reply reply = request(readRequest(options_.id, field), 1u + field.size, what);
  if (reply.status.params.size() != 1u + field.size)
    throw BusFault(std::string(what) + " of DYNAMIXEL " + where() + ": a reply of " +
                   std::to_string(reply.status.params.size() - 1) + " bytes where " + std::to_string(field.size) +
                   " were asked");
  return readLittleEndian(&reply.status.params[1], field.size);
}

void Servo::write(Field field, std::uint32_t value, const char* what) {
  const Reply reply = request(writeRequest(options_.id, field, value), kWriteStatusParams, what);
  if (const std::uint8_t error = reply.error() & ~kAlertBit; error != 0)
    throw BusFault(std::string(what) + " of DYNAMIXEL " + where() + " refused: " + processingErrorText(error));
}

void Servo::identify() {
  Reply reply;
  try {
    reply = request(Packet{options_.id, instruction::kPing, {}}, kPingStatusParams, "ping");
  } catch (const BusFault& e) {
    throw BusFault("no DYNAMIXEL answered as " + where() +
                   " (check the ID, the baud rate, the power and the cable): " + e.what());
  }
  if (reply.status.params.size() < 3) throw BusFault("DYNAMIXEL " + where() + ": a ping reply without a model number");
  const auto number = static_cast<std::uint16_t>(readLittleEndian(&reply.status.params[1], 2));
  const Model* expected = modelByName(options_.model);
  if (!expected) throw BusFault("unknown DYNAMIXEL model '" + options_.model + "'; known: " + knownModelNames());
  if (number != expected->number) {
    const Model* found = modelByNumber(number);
    throw BusFault("DYNAMIXEL " + where() + " is model " + std::to_string(number) +
                   (found ? " (" + found->name + ")" : " (not an X-series model uampc knows)") + ", the scene says " +
                   expected->name + " (" + std::to_string(expected->number) + ")");
  }
  model_ = expected;
}

// Velocity control mode (Operating Mode 1) is in EEPROM, writable only with the torque off; the bus
// watchdog is armed last, so that the set-up itself cannot trip it.
void Servo::setUp() {
  write(table::kTorqueEnable, 0, "torque off");
  if (options_.bus_watchdog_s > 0) write(table::kBusWatchdog, 0, "bus watchdog reset");
  if (read(table::kOperatingMode, "operating mode read") != kVelocityControlMode)
    write(table::kOperatingMode, kVelocityControlMode, "velocity mode");
  velocity_limit_ =
      radiansPerSecond(*model_, static_cast<std::int32_t>(read(table::kVelocityLimit, "velocity limit read")));
  write(table::kGoalVelocity, 0, "goal velocity");
  write(table::kTorqueEnable, 1, "torque on");
  rearmWatchdog();
}

void Servo::rearmWatchdog() {
  if (options_.bus_watchdog_s <= 0) return;
  // Unit 20 ms, 1..127.
  const long units = std::clamp(std::lround(options_.bus_watchdog_s / 0.02), 1L, 127L);
  write(table::kBusWatchdog, static_cast<std::uint32_t>(units), "bus watchdog");
}

double Servo::setVelocity(double radians_per_second) {
  const double applied = std::clamp(radians_per_second, -velocity_limit_, velocity_limit_);
  const auto units = static_cast<std::uint32_t>(velocityUnits(*model_, applied));
  const Reply reply =
      request(writeRequest(options_.id, table::kGoalVelocity, units), kWriteStatusParams, "goal velocity");
  const std::uint8_t error = reply.error() & ~kAlertBit;
  // The bus watchdog tripped (the bus was silent too long): Goal Velocity is refused with a data
  // range error until the watchdog is cleared and armed again.
  if (error == kDataRangeError && options_.bus_watchdog_s > 0) {
    write(table::kBusWatchdog, 0, "bus watchdog reset");
    rearmWatchdog();
    write(table::kGoalVelocity, units, "goal velocity");
  } else if (error != 0) {
    throw BusFault("goal velocity of DYNAMIXEL " + where() + " refused: " + processingErrorText(error));
  }
  return radiansPerSecond(*model_, static_cast<std::int32_t>(units));
}

ServoState Servo::readState() {
  // Present Velocity (128) and Present Position (132) are adjacent: one read of 8 bytes.
  const Field both{table::kPresentVelocity.address, 8};
  const Reply reply = request(readRequest(options_.id, both), 1u + both.size, "present velocity and position read");
  if (reply.status.params.size() != 9u)
    throw BusFault("present velocity and position read of DYNAMIXEL " + where() + ": a reply of the wrong size");
  const auto velocity = static_cast<std::int32_t>(readLittleEndian(&reply.status.params[1], 4));
  const auto position = static_cast<std::int32_t>(readLittleEndian(&reply.status.params[5], 4));
  ServoState state;
  state.velocity = radiansPerSecond(*model_, velocity);
  state.position = radians(*model_, unwrap(position));
  const auto round_trip = reply.received - reply.sent;
  state.round_trip_s = std::chrono::duration<double>(round_trip).count();
  state.stamp = reply.received - round_trip / 2;
  if (reply.error() & kAlertBit)
    state.hardware_error = static_cast<std::uint8_t>(read(table::kHardwareErrorStatus, "hardware error status read"));
  return state;
}

std::int64_t Servo::unwrap(std::int32_t raw) {
  if (!have_raw_) {
    turns_counts_ = raw;
  } else if (reconnected_) {
    // The servo may have been power-cycled (its count restarts within one turn): continue with the
    // shortest turn between the last reading and this one; whole turns made while away are unknown.
    const std::int64_t turn = model_->counts_per_turn;
    std::int64_t delta = (static_cast<std::int64_t>(raw) - last_raw_) % turn;
    if (delta >= turn / 2) delta -= turn;
    if (delta < -turn / 2) delta += turn;
    turns_counts_ += delta;
  } else {
    // int32 difference: correct across the wrap at 2^31 (two's complement).
    turns_counts_ += static_cast<std::int32_t>(static_cast<std::uint32_t>(raw) - static_cast<std::uint32_t>(last_raw_));
  }
  last_raw_ = raw;
  have_raw_ = true;
  reconnected_ = false;
  return turns_counts_;
}

void Servo::reconnect() {
  bus_.reopen();
  identify();
  setUp();
  reconnected_ = true;
}

void Servo::release() noexcept {
  try {
    if (bus_.isOpen()) bus_.transact(writeRequest(options_.id, table::kTorqueEnable, 0));
  } catch (...) {
  }
}

}  // namespace uampc::dynamixel
