#include "emulated_servo.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "write_rules.hpp"

namespace uampc::dynamixel::emulation {
namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr auto kWatchdogUnit = std::chrono::milliseconds(20);  // Bus Watchdog unit (e-manual)
constexpr auto kReturnDelayUnit = std::chrono::microseconds(2);

const Model& checkedModel(const EmulatorOptions& options) {
  const Model* model = modelByName(options.model);
  if (!model) {
    throw std::runtime_error("unknown model '" + options.model + "' (known: " + knownModelNames() + ")");
  }
  if (options.id > kMaxId) throw std::runtime_error("ID " + std::to_string(options.id) + " is not in 0-252");
  if (!(options.max_acceleration > 0.0) || !std::isfinite(options.max_acceleration)) {
    throw std::runtime_error("max_acceleration must be a positive number of rad/s^2");
  }
  if (options.velocity_limit > static_cast<std::uint32_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::runtime_error("velocity_limit must fit in int32");
  }
  return *model;
}

}  // namespace

EmulatedServo::EmulatedServo(const EmulatorOptions& options, Clock::time_point now)
    : model_(checkedModel(options)), max_acceleration_(options.max_acceleration) {
  table_.set(table::kModelNumber, model_.number);
  table_.set(field::kFirmwareVersion, options.firmware);
  table_.set(field::kId, options.id);
  table_.set(table::kVelocityLimit, options.velocity_limit);
  motor_.position = radians(model_, options.initial_position);
  power_on_ = last_update_ = last_packet_ = now;
  publishPresent(now);
}

void EmulatedServo::advanceTo(Clock::time_point now) {
  if (now <= last_update_) return;
  // The watchdog trips at its deadline, not at the next poll: the ramp-down starts exactly there.
  if (const auto deadline = watchdogDeadline(); deadline && *deadline < now) {
    integrateTo(std::max(*deadline, last_update_));
    table_.set(table::kGoalVelocity, 0);  // e-manual: "the Goal is set to 0 and the servo stops"
    table_.set(table::kBusWatchdog, kWatchdogTripped);
  }
  integrateTo(now);
  publishPresent(now);
}

bool EmulatedServo::listensTo(std::uint8_t id) const { return id == kBroadcastId || id == table_.get(field::kId); }

std::optional<Packet> EmulatedServo::execute(const Packet& instruction, Clock::time_point now) {
  if (instruction.instruction == instruction::kStatus) return std::nullopt;  // another servo's reply
  last_packet_ = now;
  const bool reply_due = owesReply(instruction);  // before a write changes Status Return Level
  Packet reply;
  switch (instruction.instruction) {
    case instruction::kPing:
      reply = ping();
      break;
    case instruction::kRead:
      reply = read(instruction.params);
      break;
    case instruction::kWrite:
      reply = write(instruction.params);
      break;
    case instruction::kReboot:
      reply = reboot(now);
      break;
    default:  // REG WRITE, ACTION, SYNC/BULK and the rest are not emulated
      reply = status(error::kInstruction);
  }
  if (!reply_due) return std::nullopt;
  return reply;
}

// Broadcast: only PING is answered. Status Return Level (68): 0 PING only, 1 also READ, 2 all.
bool EmulatedServo::owesReply(const Packet& instruction) const {
  if (instruction.instruction == instruction::kPing) return true;
  if (instruction.id == kBroadcastId) return false;
  const std::uint32_t level = table_.get(field::kStatusReturnLevel);
  return level >= 2 || (level == 1 && instruction.instruction == instruction::kRead);
}

std::optional<Packet> EmulatedServo::crcErrorReply() const {
  // The real servo answers a corrupted packet with CRC Error; its ID is unknown, so the reply
  // comes from this servo's own.
  if (table_.get(field::kStatusReturnLevel) < 2) return std::nullopt;
  return status(error::kCrc);
}

void EmulatedServo::raiseHardwareError(std::uint8_t bits) {
  if (bits == 0) return;  // only REBOOT clears the Hardware Error Status
  table_.set(table::kHardwareErrorStatus, table_.get(table::kHardwareErrorStatus) | bits);
  table_.set(table::kTorqueEnable, 0);  // the Shutdown reaction: torque off
}

void EmulatedServo::powerCycle(Clock::time_point now) {
  table_.resetRam();
  motor_.velocity = 0.0;
  // "Present Position is reset to within one turn when the power is turned on or on reboot."
  const double turn = kTwoPi;
  motor_.position = std::fmod(motor_.position, turn);
  if (motor_.position < 0.0) motor_.position += turn;
  power_on_ = last_update_ = last_packet_ = now;
  publishPresent(now);
}

std::chrono::microseconds EmulatedServo::returnDelay() const {
  return static_cast<int>(table_.get(table::kReturnDelayTime)) * kReturnDelayUnit;
}

double EmulatedServo::goalVelocity() const { return radiansPerSecond(model_, table_.getSigned(table::kGoalVelocity)); }

bool EmulatedServo::torqueEnabled() const { return table_.get(table::kTorqueEnable) != 0; }

bool EmulatedServo::watchdogTripped() const { return table_.get(table::kBusWatchdog) == kWatchdogTripped; }

Packet EmulatedServo::status(std::uint8_t error, const std::vector<std::uint8_t>& data) const {
  Packet packet{static_cast<std::uint8_t>(table_.get(field::kId)), instruction::kStatus, {}};
  // The alert bit in every status while a hardware error is set (e-manual, Status Packet).
  const bool alert = table_.get(table::kHardwareErrorStatus) != 0;
  packet.params.push_back(static_cast<std::uint8_t>(error | (alert ? kAlertBit : 0)));
  packet.params.insert(packet.params.end(), data.begin(), data.end());
  return packet;
}

Packet EmulatedServo::ping() const {
  std::vector<std::uint8_t> data;
  appendLittleEndian(data, table_.get(table::kModelNumber), 2);
  data.push_back(static_cast<std::uint8_t>(table_.get(field::kFirmwareVersion)));
  return status(0, data);
}

Packet EmulatedServo::read(const std::vector<std::uint8_t>& params) const {
  if (params.size() != 4) return status(error::kDataLength);
  const auto address = static_cast<std::uint16_t>(readLittleEndian(&params[0], 2));
  const auto length = static_cast<std::uint16_t>(readLittleEndian(&params[2], 2));
  if (length == 0 || address + length > kTableSize) return status(error::kAccess);
  return status(0, table_.read(address, length));
}

Packet EmulatedServo::write(const std::vector<std::uint8_t>& params) {
  if (params.size() < 3) return status(error::kDataLength);
  const auto address = static_cast<std::uint16_t>(readLittleEndian(&params[0], 2));
  const std::vector<std::uint8_t> data(params.begin() + 2, params.end());
  const Packet reply_as = status(0);  // the ID before a write that changes it
  if (const std::uint8_t refused = writeError(table_, address, data)) return status(refused);
  table_.write(address, data);
  return reply_as;
}

Packet EmulatedServo::reboot(Clock::time_point now) {
  Packet reply = status(0);  // the servo replies, then resets
  powerCycle(now);
  return reply;
}

std::optional<EmulatedServo::Clock::time_point> EmulatedServo::watchdogDeadline() const {
  const std::uint32_t units = table_.get(table::kBusWatchdog);
  // 0 disables it, 0xFF has tripped already; it watches only while the torque is on.
  if (units == 0 || units > kMaxBusWatchdog || !torqueEnabled()) return std::nullopt;
  return last_packet_ + static_cast<int>(units) * kWatchdogUnit;
}

void EmulatedServo::integrateTo(Clock::time_point time) {
  const double seconds = std::chrono::duration<double>(time - last_update_).count();
  motor_.advance(seconds, targetVelocity(), max_acceleration_);
  last_update_ = time;
}

// Velocity mode with the torque on tracks Goal Velocity; with the torque off the motor coasts to
// a stop. Other modes hold still: their position/current control is not emulated.
double EmulatedServo::targetVelocity() const {
  if (!torqueEnabled() || table_.get(table::kOperatingMode) != kVelocityControlMode) return 0.0;
  return goalVelocity();
}

void EmulatedServo::publishPresent(Clock::time_point now) {
  const std::int32_t velocity_units = velocityUnits(model_, motor_.velocity);
  table_.set(table::kPresentVelocity, static_cast<std::uint32_t>(velocity_units));
  // Present Position wraps like the servo's int32: the cast to uint32 is modulo 2^32.
  const auto counts = std::llround(motor_.position * model_.counts_per_turn / kTwoPi);
  table_.set(table::kPresentPosition, static_cast<std::uint32_t>(counts));
  const bool moving = static_cast<std::uint32_t>(std::abs(velocity_units)) > table_.get(field::kMovingThreshold);
  table_.set(field::kMoving, moving ? 1 : 0);
  const auto tick = std::chrono::duration_cast<std::chrono::milliseconds>(now - power_on_).count();
  table_.set(field::kRealtimeTick, static_cast<std::uint32_t>(tick % 32768));
}

}  // namespace uampc::dynamixel::emulation
