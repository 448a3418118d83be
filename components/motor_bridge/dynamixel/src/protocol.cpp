#include "uampc/dynamixel/protocol.hpp"

#include <algorithm>
#include <array>

namespace uampc::dynamixel {
namespace {

constexpr std::array<std::uint8_t, 4> kHeader{0xFF, 0xFF, 0xFD, 0x00};
constexpr std::size_t kHeaderSize = kHeader.size();
constexpr std::size_t kLengthOffset = 5;    // after the header and the ID
constexpr std::size_t kBodyOffset = 7;      // the instruction
constexpr std::size_t kMaxLength = 0xFFFF;  // LEN is 16 bits

// Inserts FD after every FF FF FD of the body (instruction and parameters).
std::vector<std::uint8_t> stuff(std::uint8_t instruction, const std::vector<std::uint8_t>& params) {
  std::vector<std::uint8_t> body{instruction};
  body.reserve(params.size() + params.size() / 3 + 1);
  for (std::uint8_t b : params) {
    body.push_back(b);
    const std::size_t n = body.size();
    if (n >= 3 && body[n - 3] == 0xFF && body[n - 2] == 0xFF && body[n - 1] == 0xFD) body.push_back(0xFD);
  }
  return body;
}

// Removes the FD that follows every FF FF FD (the inverse of stuff).
std::vector<std::uint8_t> unstuff(const std::vector<std::uint8_t>& stuffed) {
  std::vector<std::uint8_t> out;
  out.reserve(stuffed.size());
  for (std::size_t i = 0; i < stuffed.size(); ++i) {
    out.push_back(stuffed[i]);
    const std::size_t n = out.size();
    if (n >= 3 && out[n - 3] == 0xFF && out[n - 2] == 0xFF && out[n - 1] == 0xFD && i + 1 < stuffed.size() &&
        stuffed[i + 1] == 0xFD) {
      ++i;  // the stuffed byte
    }
  }
  return out;
}

}  // namespace

std::string processingErrorText(std::uint8_t error) {
  switch (error & ~kAlertBit) {
    case 0:
      return "";
    case 1:
      return "result fail";
    case 2:
      return "instruction error";
    case 3:
      return "CRC error (the servo received a corrupted packet)";
    case 4:
      return "data range error";
    case 5:
      return "data length error";
    case 6:
      return "data limit error";
    case 7:
      return "access error";
    default:
      return "unknown error " + std::to_string(error & ~kAlertBit);
  }
}

std::uint16_t crc16(const std::uint8_t* data, std::size_t size) {
  std::uint16_t crc = 0;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= static_cast<std::uint16_t>(data[i]) << 8;
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000) ? static_cast<std::uint16_t>((crc << 1) ^ 0x8005) : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

std::vector<std::uint8_t> encode(const Packet& packet) {
  const std::vector<std::uint8_t> body = stuff(packet.instruction, packet.params);
  std::vector<std::uint8_t> out(kHeader.begin(), kHeader.end());
  out.push_back(packet.id);
  appendLittleEndian(out, static_cast<std::uint32_t>(body.size() + 2), 2);
  out.insert(out.end(), body.begin(), body.end());
  appendLittleEndian(out, crc16(out.data(), out.size()), 2);
  return out;
}

void appendLittleEndian(std::vector<std::uint8_t>& out, std::uint32_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint32_t readLittleEndian(const std::uint8_t* data, int bytes) {
  std::uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) value |= static_cast<std::uint32_t>(data[i]) << (8 * i);
  return value;
}

void PacketParser::feed(const std::uint8_t* data, std::size_t size) {
  buffer_.insert(buffer_.end(), data, data + size);
}

std::optional<PacketParser::Result> PacketParser::next() {
  for (;;) {
    // Skip to the next header.
    auto header = std::search(buffer_.begin(), buffer_.end(), kHeader.begin(), kHeader.end());
    if (header == buffer_.end()) {
      // Keep a tail that may be the start of a header still arriving.
      const std::size_t keep = std::min(buffer_.size(), kHeaderSize - 1);
      buffer_.erase(buffer_.begin(), buffer_.end() - static_cast<std::ptrdiff_t>(keep));
      return std::nullopt;
    }
    buffer_.erase(buffer_.begin(), header);
    if (buffer_.size() < kBodyOffset) return std::nullopt;
    const std::size_t length = buffer_[kLengthOffset] | (buffer_[kLengthOffset + 1] << 8);
    if (length < 3 || length > kMaxLength - kBodyOffset) {  // instruction + CRC at least
      buffer_.erase(buffer_.begin(), buffer_.begin() + kHeaderSize);
      return Result{Result::Kind::kMalformed, {}};
    }
    const std::size_t total = kBodyOffset + length;
    if (buffer_.size() < total) return std::nullopt;
    std::vector<std::uint8_t> raw(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    const std::uint16_t received = static_cast<std::uint16_t>(readLittleEndian(&raw[total - 2], 2));
    if (crc16(raw.data(), total - 2) != received) {
      // Drop only the header: a real packet may start inside what looked like this one.
      buffer_.erase(buffer_.begin(), buffer_.begin() + kHeaderSize);
      return Result{Result::Kind::kCrcError, {}};
    }
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    Result result;
    result.packet.id = raw[kHeaderSize];
    result.packet.instruction = raw[kBodyOffset];
    const std::vector<std::uint8_t> stuffed(raw.begin() + kBodyOffset + 1, raw.end() - 2);
    result.packet.params = unstuff(stuffed);
    return result;
  }
}

}  // namespace uampc::dynamixel
