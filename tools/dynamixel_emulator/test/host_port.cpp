#include "host_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace uampc::dynamixel::test {

std::string uniqueLink() {
  static std::atomic<int> counter{0};
  const std::string name = "uampc-dxl-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return (std::filesystem::temp_directory_path() / name).string();
}

EmulatorOptions optionsWithLink() {
  EmulatorOptions options;
  options.link = uniqueLink();
  return options;
}

HostPort::HostPort(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd_ < 0) throw std::runtime_error("open " + path + ": " + std::strerror(errno));
  termios raw{};
  ::tcgetattr(fd_, &raw);
  ::cfmakeraw(&raw);
  ::cfsetspeed(&raw, B57600);
  ::tcsetattr(fd_, TCSANOW, &raw);
  ::tcflush(fd_, TCIOFLUSH);  // what an earlier host left unread
}

HostPort::~HostPort() { ::close(fd_); }

bool HostPort::writeBytes(const Bytes& bytes) {
  return ::write(fd_, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
}

Bytes HostPort::readBytes(std::size_t count, std::chrono::milliseconds timeout) {
  Bytes bytes;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (bytes.size() < count) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd fd{fd_, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&fd, 1, static_cast<int>(left.count())) <= 0) break;
    std::uint8_t buffer[256];
    const ssize_t n = ::read(fd_, buffer, std::min(sizeof buffer, count - bytes.size()));
    if (n <= 0) break;  // a hung-up port
    bytes.insert(bytes.end(), buffer, buffer + n);
  }
  return bytes;
}

std::optional<PacketParser::Result> HostPort::receive(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (auto result = parser_.next()) return result;
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    const Bytes bytes = readBytes(64, std::min(left, std::chrono::milliseconds(5)));
    parser_.feed(bytes.data(), bytes.size());
    if (bytes.empty() && left.count() <= 0) return std::nullopt;
  }
}

Packet HostPort::request(const Packet& instruction) {
  if (!writeBytes(encode(instruction))) throw std::runtime_error("write failed: " + std::string(std::strerror(errno)));
  const auto result = receive();
  if (!result) throw std::runtime_error("no status packet within 1 s");
  if (result->kind != PacketParser::Result::Kind::kPacket) throw std::runtime_error("a corrupt status packet");
  if (result->packet.instruction != instruction::kStatus || result->packet.params.empty()) {
    throw std::runtime_error("not a status packet");
  }
  return result->packet;
}

std::uint8_t HostPort::writeField(Field field, std::uint32_t value, std::uint8_t id) {
  return request(writePacket(id, field, value)).params[0];
}

std::uint32_t HostPort::readField(Field field, std::uint8_t id) {
  const Packet status = request(readPacket(id, field));
  // The alert bit reports a hardware error, not a failed READ: the data are there.
  if (status.params[0] & ~kAlertBit) throw std::runtime_error("read refused: " + processingErrorText(status.params[0]));
  if (status.params.size() != 1u + field.size) throw std::runtime_error("read: wrong data length");
  return readLittleEndian(&status.params[1], field.size);
}

Packet writePacket(std::uint8_t id, Field field, std::uint32_t value) {
  Packet packet{id, instruction::kWrite, {}};
  appendLittleEndian(packet.params, field.address, 2);
  appendLittleEndian(packet.params, value, field.size);
  return packet;
}

Packet readPacket(std::uint8_t id, Field field) {
  Packet packet{id, instruction::kRead, {}};
  appendLittleEndian(packet.params, field.address, 2);
  appendLittleEndian(packet.params, field.size, 2);
  return packet;
}

bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(5ms);
  }
  return true;
}

}  // namespace uampc::dynamixel::test
