#include "write_rules.hpp"

#include <cstdlib>

#include "uampc/dynamixel/protocol.hpp"

namespace uampc::dynamixel::emulation {
namespace {

// Every byte must belong to a writable field, and a field is written whole: the e-manual's Data
// Length Error is "only 2 bytes of an item defined as 4 bytes".
std::uint8_t layoutError(std::uint16_t address, std::size_t size) {
  const std::size_t end = address + size;
  for (std::size_t at = address; at < end;) {
    const FieldSpec* spec = fieldAt(static_cast<std::uint16_t>(at));
    if (!spec || !spec->writable) return error::kAccess;
    const std::size_t field_end = spec->field.address + spec->field.size;
    if (spec->field.address < address || field_end > end) return error::kDataLength;
    at = field_end;
  }
  return 0;
}

bool validOperatingMode(std::uint32_t mode) {
  // Current 0, velocity 1, position 3, extended position 4, current-based position 5, PWM 16.
  return mode == 0 || mode == 1 || mode == 3 || mode == 4 || mode == 5 || mode == 16;
}

// The values after the write, checked against the table before it.
std::uint8_t valueError(const ControlTableImage& before, const ControlTableImage& after, std::uint16_t address,
                        std::size_t size) {
  // Writes cover whole fields (layoutError), so a field is written when its first byte is.
  const auto writes = [&](Field field) { return field.address >= address && field.address < address + size; };
  const bool tripped = before.get(table::kBusWatchdog) == kWatchdogTripped;
  if (writes(table::kTorqueEnable)) {
    const std::uint32_t torque = after.get(table::kTorqueEnable);
    if (torque > 1) return error::kDataRange;
    // A hardware error keeps the torque off until REBOOT (e-manual, Hardware Error Status).
    if (torque == 1 && before.get(table::kHardwareErrorStatus) != 0) return error::kAccess;
  }
  if (writes(table::kOperatingMode) && !validOperatingMode(after.get(table::kOperatingMode))) return error::kDataRange;
  if (writes(field::kId) && after.get(field::kId) > kMaxId) return error::kDataRange;
  if (writes(field::kStatusReturnLevel) && after.get(field::kStatusReturnLevel) > 2) return error::kDataRange;
  if (writes(table::kBusWatchdog)) {
    const std::uint32_t watchdog = after.get(table::kBusWatchdog);
    // Only 0 clears a Bus Watchdog Error (e-manual, Bus Watchdog); re-arming needs that first.
    if (watchdog > kMaxBusWatchdog || (tripped && watchdog != 0)) return error::kDataRange;
  }
  if (writes(table::kGoalVelocity)) {
    // "If Goal Velocity is changed after a Bus Watchdog Error, a Range Error is returned."
    if (tripped) return error::kDataRange;
    const std::int64_t goal = after.getSigned(table::kGoalVelocity);
    if (std::llabs(goal) > after.get(table::kVelocityLimit)) return error::kDataLimit;
  }
  return 0;
}

}  // namespace

std::uint8_t writeError(const ControlTableImage& table, std::uint16_t address, const std::vector<std::uint8_t>& data) {
  if (data.empty()) return error::kDataLength;
  if (address + data.size() > kTableSize) return error::kAccess;
  if (const std::uint8_t layout = layoutError(address, data.size())) return layout;
  // "EEPROM area can be written only when Torque Enable is 0" - else Access Error.
  if (address < kEepromEnd && table.get(table::kTorqueEnable) != 0) return error::kAccess;
  ControlTableImage after = table;
  after.write(address, data);
  return valueError(table, after, address, data.size());
}

}  // namespace uampc::dynamixel::emulation
