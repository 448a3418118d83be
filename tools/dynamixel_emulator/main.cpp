// dynamixel_emulator: an emulated X-series servo on a pseudo-terminal, served until Ctrl-C, for
// running the motor bridge without hardware (point its port at --link).
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
#include "uampc/dynamixel/control_table.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace uampc::dynamixel {
namespace {

void printUsage(std::FILE* out) {
  std::fprintf(out,
               "usage: dynamixel_emulator --link PATH [--id N] [--model NAME] [--firmware N] [--velocity-limit N]\n"
               "                          [--max-acceleration RAD_S2] [--initial-position COUNTS]\n"
               "Serves an emulated DYNAMIXEL X-series servo (Protocol 2.0) on a pseudo-terminal, linked at PATH,\n"
               "until SIGINT or SIGTERM.\n"
               "  --link PATH              symlink to the pty's slave, the port the host opens (required)\n"
               "  --id N                   servo ID, 0-252 (default 1)\n"
               "  --model NAME             one of %s (default XM430-W350)\n"
               "  --firmware N             firmware version that PING reports (default 46)\n"
               "  --velocity-limit N       Velocity Limit (address 44), velocity units (default 265)\n"
               "  --max-acceleration X     the motor's acceleration, rad/s^2 (default 50)\n"
               "  --initial-position N     Present Position at power-on, counts (default 0)\n",
               knownModelNames().c_str());
}

// An integer flag read strictly: "12x", "1.5" or out of [low, high] is an error naming the flag.
long long integer(const std::string& flag, const std::string& text, long long low, long long high) {
  const double value = tools::number(flag, text);
  if (value != std::floor(value) || value < static_cast<double>(low) || value > static_cast<double>(high)) {
    throw std::invalid_argument(flag + ": '" + text + "' is not an integer in [" + std::to_string(low) + ", " +
                                std::to_string(high) + "]");
  }
  return static_cast<long long>(value);
}

void setOption(EmulatorOptions& options, const std::string& flag, const std::string& value) {
  constexpr long long kInt32Max = std::numeric_limits<std::int32_t>::max();
  if (flag == "--link") {
    options.link = value;
  } else if (flag == "--id") {
    options.id = static_cast<std::uint8_t>(integer(flag, value, 0, kMaxId));
  } else if (flag == "--model") {
    if (!modelByName(value))
      throw std::invalid_argument("unknown model '" + value + "' (known: " + knownModelNames() + ")");
    options.model = value;
  } else if (flag == "--firmware") {
    options.firmware = static_cast<std::uint8_t>(integer(flag, value, 0, 255));
  } else if (flag == "--velocity-limit") {
    options.velocity_limit = static_cast<std::uint32_t>(integer(flag, value, 0, kInt32Max));
  } else if (flag == "--max-acceleration") {
    options.max_acceleration = tools::number(flag, value);
    if (options.max_acceleration <= 0.0) throw std::invalid_argument(flag + ": must be positive");
  } else if (flag == "--initial-position") {
    options.initial_position = static_cast<std::int32_t>(integer(flag, value, -kInt32Max - 1, kInt32Max));
  } else {
    throw std::invalid_argument("unknown option '" + flag + "'");
  }
}

EmulatorOptions parse(int argc, char** argv) {
  EmulatorOptions options;
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw std::invalid_argument(flag + " needs a value");
    setOption(options, flag, argv[i + 1]);
  }
  if (options.link.empty()) throw std::invalid_argument("--link PATH is required");
  return options;
}

int run(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      printUsage(stdout);
      return 0;
    }
  }
  EmulatorOptions options;
  try {
    options = parse(argc, argv);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "dynamixel_emulator: %s (see --help)\n", e.what());
    return 2;
  }
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
