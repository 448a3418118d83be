// A serial port in raw mode (termios), 8N1 as DYNAMIXEL buses run, with reads bounded by a deadline
// so that a silent or unplugged bus never blocks the caller.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace uampc::dynamixel {

using SteadyClock = std::chrono::steady_clock;

// The port failed (unplugged adapter, closed pseudo-terminal): every call after this fails too
// until the port is opened again.
struct SerialError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The baud rates DYNAMIXEL X-series servos support (Baud Rate, address 8) and termios knows.
bool isSupportedBaudRate(int baud_rate);
std::string supportedBaudRates();

class SerialPort {
 public:
  // Opens `path` (a tty, a pseudo-terminal or a symlink to one) at `baud_rate`; throws SerialError
  // naming the path and the reason.
  SerialPort(const std::string& path, int baud_rate);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  void write(const std::vector<std::uint8_t>& bytes);
  // Up to `size` bytes that arrive before `deadline`; 0 at the deadline.
  std::size_t read(std::uint8_t* buffer, std::size_t size, SteadyClock::time_point deadline);
  // Drops bytes received but not yet read (a late reply to an earlier request).
  void discardInput();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what) const;

  std::string path_;
  int fd_ = -1;
};

}  // namespace uampc::dynamixel
