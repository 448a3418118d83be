// dynamixel_emulator: an emulated X-series servo on a pseudo-terminal, served until Ctrl-C, for
// running the motor bridge without hardware (point its port at --link).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "servo_emulator.hpp"
#include "tool_main.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/dynamixel/control_table.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace uampc::dynamixel {
namespace {

// The options, each checked as it is read (CLI11): a bad one exits 2 naming it.
// id and firmware are read as int: CLI11 takes a std::uint8_t option as a character.
struct ByteOptions {
  int id = 1, firmware = 46;
};

void addOptions(CLI::App& app, EmulatorOptions& o, ByteOptions& bytes) {
  app.add_option("--link", o.link, "symlink to the pty's slave, the port the host opens")->required()->type_name("PATH");
  bytes = {o.id, o.firmware};
  app.add_option("--id", bytes.id, "servo ID")->check(CLI::Range(0, static_cast<int>(kMaxId)))->capture_default_str();
  app.add_option("--model", o.model, "one of " + knownModelNames())
      ->check([](const std::string& name) {
        return modelByName(name) ? std::string() : "unknown model '" + name + "' (known: " + knownModelNames() + ")";
      })
      ->capture_default_str();
  app.add_option("--firmware", bytes.firmware, "firmware version that PING reports")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  app.add_option("--velocity-limit", o.velocity_limit, "Velocity Limit (address 44), velocity units")
      ->check(CLI::Range(0L, static_cast<long>(std::numeric_limits<std::int32_t>::max())))
      ->capture_default_str();
  app.add_option("--max-acceleration", o.max_acceleration, "the motor's acceleration, rad/s^2")
      ->check(command_line::kFinitePositive)
      ->capture_default_str();
  app.add_option("--initial-position", o.initial_position, "Present Position at power-on, counts")
      ->capture_default_str();
}

int run(int argc, char** argv) {
  CLI::App app{
      "Serves an emulated DYNAMIXEL X-series servo (Protocol 2.0) on a pseudo-terminal, linked at PATH, until\n"
      "SIGINT or SIGTERM.",
      "dynamixel_emulator"};
  EmulatorOptions options;
  ByteOptions bytes;
  addOptions(app, options, bytes);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  options.id = static_cast<std::uint8_t>(bytes.id);
  options.firmware = static_cast<std::uint8_t>(bytes.firmware);
  catchStopSignals();  // before the pty exists: a signal now still removes the link on the way out
  ServoEmulator servo(options);
  std::printf("dynamixel_emulator: %s ID %d on %s -> %s\n", options.model.c_str(), options.id, servo.port().c_str(),
              std::filesystem::read_symlink(servo.port()).c_str());
  std::fflush(stdout);
  while (!stopRequested()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::printf("dynamixel_emulator: stopped; %llu packets (%llu corrupt), %llu bytes received, %llu sent\n",
              static_cast<unsigned long long>(servo.packetsReceived()),
              static_cast<unsigned long long>(servo.corruptPacketsReceived()),
              static_cast<unsigned long long>(servo.bytesReceived()),
              static_cast<unsigned long long>(servo.bytesSent()));
  return 0;
}

}  // namespace
}  // namespace uampc::dynamixel

int main(int argc, char** argv) {
  return uampc::tools::runTool("dynamixel_emulator", uampc::dynamixel::run, argc, argv);
}
