#include "uampc/dynamixel/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace uampc::dynamixel {
namespace {

const std::pair<int, speed_t> kBaudRates[] = {{9600, B9600},       {57600, B57600},     {115200, B115200},
                                              {1000000, B1000000}, {2000000, B2000000}, {3000000, B3000000},
                                              {4000000, B4000000}};

speed_t termiosSpeed(int baud_rate) {
  for (const auto& [rate, speed] : kBaudRates)
    if (rate == baud_rate) return speed;
  return B0;
}

}  // namespace

bool isSupportedBaudRate(int baud_rate) { return termiosSpeed(baud_rate) != B0; }

std::string supportedBaudRates() {
  std::string rates;
  for (const auto& entry : kBaudRates) rates += (rates.empty() ? "" : ", ") + std::to_string(entry.first);
  return rates;
}

SerialPort::SerialPort(const std::string& path, int baud_rate) : path_(path) {
  if (!isSupportedBaudRate(baud_rate))
    throw SerialError("serial port " + path + ": baud rate " + std::to_string(baud_rate) + " is not one of " +
                      supportedBaudRates());
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) fail("cannot open");
  termios tio{};
  if (tcgetattr(fd_, &tio) != 0) fail("is not a serial port (tcgetattr)");
  cfmakeraw(&tio);  // 8 data bits, no parity, no echo, no line editing
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CSTOPB | CRTSCTS);  // 1 stop bit, no hardware flow control
  cfsetispeed(&tio, termiosSpeed(baud_rate));
  cfsetospeed(&tio, termiosSpeed(baud_rate));
  if (tcsetattr(fd_, TCSANOW, &tio) != 0) fail("cannot be configured (tcsetattr)");
  discardInput();
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

void SerialPort::fail(const std::string& what) const {
  throw SerialError("serial port " + path_ + ": " + what + ": " + std::strerror(errno));
}

void SerialPort::write(const std::vector<std::uint8_t>& bytes) {
  std::size_t done = 0;
  const auto deadline = SteadyClock::now() + std::chrono::milliseconds(100);
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) fail("write failed");
    // Output buffer full: a bus this slow is as good as gone after 100 ms.
    if (SteadyClock::now() > deadline) throw SerialError("serial port " + path_ + ": write timed out");
    pollfd p{fd_, POLLOUT, 0};
    ::poll(&p, 1, 1);
  }
}

std::size_t SerialPort::read(std::uint8_t* buffer, std::size_t size, SteadyClock::time_point deadline) {
  for (;;) {
    const ssize_t n = ::read(fd_, buffer, size);
    if (n > 0) return static_cast<std::size_t>(n);
    if (n < 0 && errno != EAGAIN && errno != EINTR) fail("read failed");
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - SteadyClock::now());
    if (left.count() <= 0) return 0;
    pollfd p{fd_, POLLIN, 0};
    // poll counts in milliseconds: round up so that a short timeout still waits.
    const int r = ::poll(&p, 1, static_cast<int>((left.count() + 999) / 1000));
    if (r > 0 && (p.revents & (POLLHUP | POLLERR)) && !(p.revents & POLLIN)) {
      errno = EIO;
      fail("device gone (hang-up)");
    }
  }
}

void SerialPort::discardInput() { tcflush(fd_, TCIFLUSH); }

}  // namespace uampc::dynamixel
