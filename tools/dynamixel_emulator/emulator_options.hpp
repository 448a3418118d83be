// What an emulated servo is: its ID, model and the limits a test wants to vary.
#pragma once

#include <cstdint>
#include <string>

namespace uampc::dynamixel {

struct EmulatorOptions {
  std::string link;  // a symlink created to the pty's slave (like udev's /dev/serial/by-id); required
  std::uint8_t id = 1;
  std::string model = "XM430-W350";  // from knownModels(); ping reports its number
  std::uint8_t firmware = 46;
  std::uint32_t velocity_limit = 265;  // Velocity Limit (address 44), velocity units
  double max_acceleration = 50.0;      // rad/s^2, the motor's dynamics
  std::int32_t initial_position = 0;   // Present Position counts at power-on (to test int32 wrap)
};

}  // namespace uampc::dynamixel
