// Whether the servo accepts a WRITE, by the X-series e-manual's rules: the processing error it
// answers with (the status packet's error byte, bits 0-6), 0 when it writes.
#pragma once

#include <cstdint>
#include <vector>

#include "control_table_image.hpp"

namespace uampc::dynamixel::emulation {

// Protocol 2.0 processing errors (e-manual, "Status Packet").
namespace error {
constexpr std::uint8_t kInstruction = 2;  // undefined instruction
constexpr std::uint8_t kCrc = 3;          // the instruction packet's CRC did not match
constexpr std::uint8_t kDataRange = 4;    // the value is out of the field's range
constexpr std::uint8_t kDataLength = 5;   // shorter than the field(s) it writes
constexpr std::uint8_t kDataLimit = 6;    // beyond the limit set in the table (Velocity Limit)
constexpr std::uint8_t kAccess = 7;       // read-only, undefined, or EEPROM with the torque on
}  // namespace error

constexpr std::uint8_t kMaxBusWatchdog = 127;    // 1-127 arm it (x 20 ms)
constexpr std::uint8_t kWatchdogTripped = 0xFF;  // -1: Bus Watchdog Error

std::uint8_t writeError(const ControlTableImage& table, std::uint16_t address, const std::vector<std::uint8_t>& data);

}  // namespace uampc::dynamixel::emulation
