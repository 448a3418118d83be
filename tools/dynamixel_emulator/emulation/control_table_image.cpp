#include "control_table_image.hpp"

#include <algorithm>

#include "uampc/dynamixel/protocol.hpp"

namespace uampc::dynamixel::emulation {

const std::vector<FieldSpec>& fieldSpecs() {
  constexpr bool R = false;  // read-only
  constexpr bool W = true;
  // XM430-W350 e-manual, control table. The model number, firmware, ID, Velocity Limit and
  // Return Delay Time (0 here, 250 = 500 us on a new servo) are set from EmulatorOptions.
  static const std::vector<FieldSpec> kSpecs = {
      {{0, 2}, R, 1020},  {{2, 4}, R, 0},      {{6, 1}, R, 0},     {{7, 1}, W, 1},     {{8, 1}, W, 1},
      {{9, 1}, W, 0},     {{10, 1}, W, 0},     {{11, 1}, W, 3},    {{12, 1}, W, 255},  {{13, 1}, W, 2},
      {{20, 4}, W, 0},    {{24, 4}, W, 10},    {{31, 1}, W, 80},   {{32, 2}, W, 160},  {{34, 2}, W, 95},
      {{36, 2}, W, 885},  {{38, 2}, W, 1193},  {{44, 4}, W, 200},  {{48, 4}, W, 4095}, {{52, 4}, W, 0},
      {{56, 1}, W, 0},    {{63, 1}, W, 52},    {{64, 1}, W, 0},    {{65, 1}, W, 0},    {{68, 1}, W, 2},
      {{69, 1}, R, 0},    {{70, 1}, R, 0},     {{76, 2}, W, 1920}, {{78, 2}, W, 100},  {{80, 2}, W, 0},
      {{82, 2}, W, 0},    {{84, 2}, W, 800},   {{88, 2}, W, 0},    {{90, 2}, W, 0},    {{98, 1}, W, 0},
      {{100, 2}, W, 885}, {{102, 2}, W, 1193}, {{104, 4}, W, 0},   {{108, 4}, W, 0},   {{112, 4}, W, 0},
      {{116, 4}, W, 0},   {{120, 2}, R, 0},    {{122, 1}, R, 0},   {{123, 1}, R, 0},   {{124, 2}, R, 0},
      {{126, 2}, R, 0},   {{128, 4}, R, 0},    {{132, 4}, R, 0},   {{136, 4}, R, 0},   {{140, 4}, R, 0},
      {{144, 2}, R, 120}, {{146, 1}, R, 30},
  };
  return kSpecs;
}

const FieldSpec* fieldAt(std::uint16_t address) {
  for (const FieldSpec& spec : fieldSpecs()) {
    if (address >= spec.field.address && address < spec.field.address + spec.field.size) return &spec;
  }
  return nullptr;
}

ControlTableImage::ControlTableImage() {
  for (const FieldSpec& spec : fieldSpecs()) set(spec.field, spec.initial);
}

std::uint32_t ControlTableImage::get(Field field) const { return readLittleEndian(&bytes_[field.address], field.size); }

std::int32_t ControlTableImage::getSigned(Field field) const {
  return static_cast<std::int32_t>(get(field));  // two's complement, as the servo stores it
}

void ControlTableImage::set(Field field, std::uint32_t value) {
  for (int i = 0; i < field.size; ++i) bytes_[field.address + i] = static_cast<std::uint8_t>(value >> (8 * i));
}

void ControlTableImage::write(std::uint16_t address, const std::vector<std::uint8_t>& data) {
  std::copy(data.begin(), data.end(), bytes_.begin() + address);
}

std::vector<std::uint8_t> ControlTableImage::read(std::uint16_t address, std::uint16_t length) const {
  return std::vector<std::uint8_t>(bytes_.begin() + address, bytes_.begin() + address + length);
}

void ControlTableImage::resetRam() {
  for (const FieldSpec& spec : fieldSpecs()) {
    if (spec.field.address >= kEepromEnd) set(spec.field, spec.initial);
  }
}

}  // namespace uampc::dynamixel::emulation
