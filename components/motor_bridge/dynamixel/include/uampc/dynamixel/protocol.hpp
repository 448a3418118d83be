// ROBOTIS DYNAMIXEL Protocol 2.0: packets, CRC-16 and byte stuffing (docs/user/rig.md).
//
// A packet on the wire: FF FF FD 00 | ID | LEN_L LEN_H | INSTRUCTION | PARAMETERS... | CRC_L CRC_H.
// LEN counts the instruction, the (stuffed) parameters and the CRC. Whenever FF FF FD appears
// after the header, the sender inserts an FD ("byte stuffing") so that a receiver never mistakes
// data for a header; the CRC is computed over the stuffed packet. A status packet is instruction
// 0x55 whose first parameter is the error byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace uampc::dynamixel {

namespace instruction {
constexpr std::uint8_t kPing = 0x01;
constexpr std::uint8_t kRead = 0x02;
constexpr std::uint8_t kWrite = 0x03;
constexpr std::uint8_t kReboot = 0x08;
constexpr std::uint8_t kStatus = 0x55;
}  // namespace instruction

constexpr std::uint8_t kBroadcastId = 0xFE;
constexpr std::uint8_t kMaxId = 252;

// The status packet's error byte: bit 7 says the servo has a hardware error (read address 70 for
// which); bits 0-6 are the processing error of this instruction.
constexpr std::uint8_t kAlertBit = 0x80;
std::string processingErrorText(std::uint8_t error);  // "" for 0

struct Packet {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::vector<std::uint8_t> params;  // unstuffed; for a status packet params[0] is the error byte
};

// CRC-16 of Protocol 2.0: polynomial 0x8005, initial value 0, no reflection (CRC-16/BUYPASS).
std::uint16_t crc16(const std::uint8_t* data, std::size_t size);

// The bytes on the wire: header, stuffing, length and CRC.
std::vector<std::uint8_t> encode(const Packet& packet);

// Little-endian fields, as every multi-byte field of the protocol and the control table is.
void appendLittleEndian(std::vector<std::uint8_t>& out, std::uint32_t value, int bytes);
std::uint32_t readLittleEndian(const std::uint8_t* data, int bytes);

// Reassembles packets from a byte stream that may split, join or garble them. Garbage before a
// header is skipped; a packet whose CRC does not match is reported once and dropped.
class PacketParser {
 public:
  struct Result {
    enum class Kind { kPacket, kCrcError, kMalformed } kind = Kind::kPacket;
    Packet packet;  // kPacket only
  };

  void feed(const std::uint8_t* data, std::size_t size);
  // The next complete packet or error, or nothing until more bytes arrive.
  std::optional<Result> next();
  void clear() { buffer_.clear(); }

 private:
  std::deque<std::uint8_t> buffer_;
};

}  // namespace uampc::dynamixel
