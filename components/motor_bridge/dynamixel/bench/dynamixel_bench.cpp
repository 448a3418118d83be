// The DYNAMIXEL figures of docs/user/rig.md ("Figures"), measured against the emulated
// XM430 on a pseudo-terminal (tools/dynamixel_emulator): a bench command that prints them, so that
// the tests only assert behaviour.
//
//   dynamixel_bench [--reads N]
//
// - bus budget: bytes of an encoder read and of a command (from the bus's counters), their time on
//   the wire at 1 Mbps (8N1: 10 bits a byte) and the share of the bus at 200 Hz reads + 10 Hz
//   commands;
// - round trip of an encoder read over the pty, host to emulator and back (median, p99): the host's
//   side of the latency; a USB adapter adds its own (an FTDI's latency timer: 1-16 ms);
// - how long each fault takes to detect: three corrupt replies, a silent servo (3 x 20 ms reply
//   timeouts), a pulled cable; and the reconnection after the cable is back.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "servo_emulator.hpp"
#include "uampc/dynamixel/servo.hpp"

namespace {

using namespace uampc::dynamixel;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

EmulatorOptions emulated(const std::string& name) {
  EmulatorOptions o;
  o.link = (std::filesystem::temp_directory_path() / ("uampc_dxl_bench_" + name + "_" + std::to_string(getpid()))).string();
  o.id = 1;
  o.model = "XM430-W350";
  return o;
}

ServoOptions servoOn(const ServoEmulator& emulator, double reply_timeout_s) {
  ServoOptions o;
  o.port = emulator.port();
  o.reply_timeout_s = reply_timeout_s;
  o.max_retries = 2;
  o.bus_watchdog_s = 0;  // the bench pauses between its parts
  return o;
}

void busBudget() {
  ServoEmulator emulator(emulated("budget"));
  Servo servo(servoOn(emulator, 0.1));
  const BusCounters start = servo.bus().counters();
  servo.readState();
  const BusCounters read = servo.bus().counters();
  servo.setVelocity(1.0);
  const BusCounters command = servo.bus().counters();
  const double read_bytes = double(read.bytes_sent - start.bytes_sent + read.bytes_received - start.bytes_received);
  const double command_bytes =
      double(command.bytes_sent - read.bytes_sent + command.bytes_received - read.bytes_received);
  const double read_us = read_bytes * 10.0, command_us = command_bytes * 10.0;  // at 1 Mbps, 8N1
  std::printf("bus budget at 1 Mbps: encoder read %.0f bytes = %.0f us, command %.0f bytes = %.0f us on the wire\n",
              read_bytes, read_us, command_bytes, command_us);
  std::printf("  200 Hz reads + 10 Hz commands: %.1f %% of the bus; %.1f %% with the factory Return Delay Time "
              "(0.5 ms per status)\n",
              (200 * read_us + 10 * command_us) / 1e4, (200 * (read_us + 500) + 10 * (command_us + 500)) / 1e4);
}

void roundTrips(int reads) {
  ServoEmulator emulator(emulated("round_trip"));
  Servo servo(servoOn(emulator, 0.1));
  servo.setVelocity(3.0);
  std::vector<double> ms;
  for (int i = 0; i < reads; ++i) {
    ms.push_back(servo.readState().round_trip_s * 1e3);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // the encoder rate, 200 Hz
  }
  std::sort(ms.begin(), ms.end());
  std::printf("encoder read round trip over the pty (%d reads at 200 Hz): median %.3f ms, p99 %.3f ms, max %.3f ms\n",
              reads, ms[ms.size() / 2], ms[ms.size() * 99 / 100], ms.back());
}

// How long a read takes to fail, ms; throws if it does not fail (the figure would be a lie).
double msUntilReadFails(Servo& servo, const char* fault) {
  const auto start = Clock::now();
  try {
    servo.readState();
  } catch (const BusFault&) {
    return msSince(start);
  }
  throw std::runtime_error(std::string("a read succeeded despite ") + fault);
}

void faults() {
  {
    ServoEmulator emulator(emulated("corrupt"));
    Servo servo(servoOn(emulator, 0.1));
    emulator.corruptReplies(3);  // 1 + max_retries
    std::printf("three corrupt replies: the read fails after %.1f ms\n", msUntilReadFails(servo, "corrupt replies"));
  }
  {
    ServoEmulator emulator(emulated("silent"));
    Servo servo(servoOn(emulator, 0.02));
    emulator.setSilent(true);
    std::printf("a silent servo (reply_timeout 20 ms, 2 retries): detected after %.1f ms\n",
                msUntilReadFails(servo, "a silent servo"));
  }
  {
    ServoEmulator emulator(emulated("unplug"));
    Servo servo(servoOn(emulator, 0.1));
    servo.readState();
    emulator.unplug();
    std::printf("a pulled cable: the next read fails after %.2f ms\n", msUntilReadFails(servo, "a pulled cable"));
    emulator.replug();
    const auto start = Clock::now();
    servo.reconnect();
    std::printf("  the cable back: reconnected (ping, model, set-up, torque on) in %.1f ms\n", msSince(start));
  }
}

}  // namespace

int main(int argc, char** argv) {
  int reads = 1000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reads" && i + 1 < argc && std::atoi(argv[i + 1]) > 0) {
      reads = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: dynamixel_bench [--reads N]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  try {
    busBudget();
    roundTrips(reads);
    faults();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dynamixel_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
