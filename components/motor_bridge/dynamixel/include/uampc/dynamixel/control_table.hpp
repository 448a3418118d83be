// The part of the DYNAMIXEL X-series control table (Protocol 2.0) that the motor bridge uses, and
// the models it knows. The addresses are the same on every X-series servo (XL430, XM430, XM540,
// XH430); the models differ in their model number (and their Velocity Limit, read from the servo).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uampc::dynamixel {

struct Field {
  std::uint16_t address;
  std::uint8_t size;  // bytes
};

namespace table {
constexpr Field kModelNumber{0, 2};
constexpr Field kReturnDelayTime{9, 1};  // unit 2 us (EEPROM)
constexpr Field kOperatingMode{11, 1};   // EEPROM: written with the torque off
constexpr Field kVelocityLimit{44, 4};   // velocity units (EEPROM)
constexpr Field kTorqueEnable{64, 1};
constexpr Field kHardwareErrorStatus{70, 1};
constexpr Field kBusWatchdog{98, 1};  // unit 20 ms; 0 disables; the servo stops when the bus falls silent
constexpr Field kGoalVelocity{104, 4};
constexpr Field kPresentVelocity{128, 4};
constexpr Field kPresentPosition{132, 4};
}  // namespace table

constexpr std::uint8_t kVelocityControlMode = 1;  // Operating Mode 1

// Hardware Error Status (address 70) bits, as the e-manual names them.
std::string hardwareErrorText(std::uint8_t status);  // "" for 0

struct Model {
  std::string name;
  std::uint16_t number;
  double velocity_unit_rpm;       // rev/min per Goal/Present Velocity unit
  std::uint32_t counts_per_turn;  // Present Position counts per revolution
};

const std::vector<Model>& knownModels();
const Model* modelByName(const std::string& name);
const Model* modelByNumber(std::uint16_t number);
std::string knownModelNames();  // "XL430-W250, XM430-W210, ..."

// Unit conversions of the control table.
double radiansPerSecond(const Model& model, std::int32_t velocity_units);
std::int32_t velocityUnits(const Model& model, double radians_per_second);  // rounded to the nearest unit
double radians(const Model& model, std::int64_t counts);

}  // namespace uampc::dynamixel
