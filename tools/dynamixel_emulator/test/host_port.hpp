// The host's side of the emulated wire, as the motor bridge would have it: the link opened with
// plain open()/termios, packets written and read with our codec. Nothing of the emulator's inside.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "emulator_options.hpp"
#include "uampc/dynamixel/control_table.hpp"
#include "uampc/dynamixel/protocol.hpp"

namespace uampc::dynamixel::test {

using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

// A link path of its own for every emulator of every test process (ctest runs them in parallel).
std::string uniqueLink();
EmulatorOptions optionsWithLink();

class HostPort {
 public:
  explicit HostPort(const std::string& path);  // throws std::runtime_error when open() fails
  ~HostPort();
  HostPort(const HostPort&) = delete;
  HostPort& operator=(const HostPort&) = delete;

  bool writeBytes(const Bytes& bytes);  // false when write() fails (an unplugged adapter)
  // Whatever arrives until `count` bytes or `timeout`.
  Bytes readBytes(std::size_t count, std::chrono::milliseconds timeout);
  // The next packet or CRC error within `timeout`; nothing if the servo stays silent.
  std::optional<PacketParser::Result> receive(std::chrono::milliseconds timeout = 1000ms);
  // One instruction and its status packet; throws std::runtime_error on silence or a bad CRC.
  Packet request(const Packet& instruction);

  std::uint8_t writeField(Field field, std::uint32_t value, std::uint8_t id = 1);  // the status's error byte
  std::uint32_t readField(Field field, std::uint8_t id = 1);                       // throws on an error
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
  PacketParser parser_;
};

Packet writePacket(std::uint8_t id, Field field, std::uint32_t value);
Packet readPacket(std::uint8_t id, Field field);
// Polls `condition` every few milliseconds until it holds or `timeout` passes.
bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout = 3000ms);

}  // namespace uampc::dynamixel::test
