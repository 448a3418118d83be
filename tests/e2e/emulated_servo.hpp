// An emulated XM430 on a pseudo-terminal for the e2e tests of the motor bridge's DYNAMIXEL backend
// (tools/dynamixel_emulator), its link named after the test and this process.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include "servo_emulator.hpp"

namespace uampc::test {

inline dynamixel::EmulatorOptions emulated(const std::string& name) {
  dynamixel::EmulatorOptions o;
  o.link =
      (std::filesystem::temp_directory_path() / ("uampc_dxl_e2e_" + name + "_" + std::to_string(getpid()))).string();
  o.model = "XM430-W350";
  o.velocity_limit = 265;
  o.max_acceleration = 50.0;
  return o;
}

}  // namespace uampc::test
