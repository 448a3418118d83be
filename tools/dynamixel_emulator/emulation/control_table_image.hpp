// The emulated servo's control table: the X-series layout (XM430-W350 e-manual, "Control Table":
// addresses, sizes, access and factory defaults) over a little-endian byte image.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "uampc/dynamixel/control_table.hpp"

namespace uampc::dynamixel::emulation {

// Fields the bridge's subset (control_table.hpp) does not name.
namespace field {
constexpr Field kFirmwareVersion{6, 1};
constexpr Field kId{7, 1};
constexpr Field kMovingThreshold{24, 4};  // velocity units; Moving (122) is 1 above it
constexpr Field kStatusReturnLevel{68, 1};
constexpr Field kRealtimeTick{120, 2};  // ms, wraps at 32768
constexpr Field kMoving{122, 1};
}  // namespace field

constexpr std::uint16_t kEepromEnd = 64;  // below: EEPROM, written only with the torque off
constexpr std::size_t kTableSize = 256;   // up to Present Temperature (146); no indirect addresses

struct FieldSpec {
  Field field;
  bool writable;
  std::uint32_t initial;  // the factory default (EEPROM) or the power-on value (RAM)
};

// The X-series fields in address order; a byte outside them is a reserved gap.
const std::vector<FieldSpec>& fieldSpecs();
const FieldSpec* fieldAt(std::uint16_t address);  // the field holding this byte, or nullptr

class ControlTableImage {
 public:
  ControlTableImage();  // every field at its factory default

  std::uint32_t get(Field field) const;
  std::int32_t getSigned(Field field) const;  // a 4-byte field as int32
  void set(Field field, std::uint32_t value);
  void write(std::uint16_t address, const std::vector<std::uint8_t>& data);  // caller checked the range
  std::vector<std::uint8_t> read(std::uint16_t address, std::uint16_t length) const;
  void resetRam();  // the RAM area (64 and up) at its power-on values; EEPROM survives power cycles

 private:
  std::array<std::uint8_t, kTableSize> bytes_{};
};

}  // namespace uampc::dynamixel::emulation
