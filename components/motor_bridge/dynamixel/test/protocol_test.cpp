// Protocol 2.0 packets against the byte-exact examples of the ROBOTIS e-manual (Protocol 2.0 page),
// so that CRC, length and stuffing are checked against the protocol's owner, not against ourselves.
#include <gtest/gtest.h>

#include <cmath>

#include "uampc/dynamixel/control_table.hpp"
#include "uampc/dynamixel/protocol.hpp"

namespace uampc::dynamixel {
namespace {

using Bytes = std::vector<std::uint8_t>;

Packet packet(std::uint8_t id, std::uint8_t instruction, Bytes params) { return Packet{id, instruction, params}; }

TEST(DynamixelProtocol, EncodesTheManualsExamples) {
  // Ping ID 1.
  EXPECT_EQ(encode(packet(1, instruction::kPing, {})),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E}));
  // Read 4 bytes at 132 (Present Position) of ID 1.
  EXPECT_EQ(encode(packet(1, instruction::kRead, {0x84, 0x00, 0x04, 0x00})),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x02, 0x84, 0x00, 0x04, 0x00, 0x1D, 0x15}));
  // Write 512 at 116 (Goal Position) of ID 1.
  EXPECT_EQ(encode(packet(1, instruction::kWrite, {0x74, 0x00, 0x00, 0x02, 0x00, 0x00})),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x09, 0x00, 0x03, 0x74, 0x00, 0x00, 0x02, 0x00, 0x00, 0xCA, 0x89}));
  // Status packets: ping reply (model 1030, firmware 38), read reply (position 166), write reply.
  EXPECT_EQ(encode(packet(1, instruction::kStatus, {0x00, 0x06, 0x04, 0x26})),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x55, 0x00, 0x06, 0x04, 0x26, 0x65, 0x5D}));
  EXPECT_EQ(encode(packet(1, instruction::kStatus, {0x00, 0xA6, 0x00, 0x00, 0x00})),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x55, 0x00, 0xA6, 0x00, 0x00, 0x00, 0x8C, 0xC0}));
  EXPECT_EQ(encode(packet(1, instruction::kStatus, {0x00})),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x55, 0x00, 0xA1, 0x0C}));
}

TEST(DynamixelProtocol, StuffsAHeaderInsideTheParametersAndParsesItBack) {
  const Packet original = packet(3, instruction::kWrite, {0x68, 0x00, 0xFF, 0xFF, 0xFD, 0x01, 0xFF, 0xFF, 0xFD});
  const Bytes wire = encode(original);
  // Two FDs inserted, and counted in LEN: instruction + 9 params + 2 stuffed + CRC = 14.
  EXPECT_EQ(wire.size(), 7u + 14u);
  EXPECT_EQ(wire[5] | (wire[6] << 8), 14);
  EXPECT_EQ((Bytes(wire.begin() + 10, wire.begin() + 14)), (Bytes{0xFF, 0xFF, 0xFD, 0xFD}));
  PacketParser parser;
  parser.feed(wire.data(), wire.size());
  const auto result = parser.next();
  ASSERT_TRUE(result);
  ASSERT_EQ(result->kind, PacketParser::Result::Kind::kPacket);
  EXPECT_EQ(result->packet.id, 3);
  EXPECT_EQ(result->packet.instruction, instruction::kWrite);
  EXPECT_EQ(result->packet.params, original.params);
}

TEST(DynamixelProtocol, ReassemblesSplitPacketsSkipsGarbageAndReportsCorruptOnes) {
  const Bytes first = encode(packet(1, instruction::kStatus, {0x00, 0xA6, 0x00, 0x00, 0x00}));
  Bytes corrupt = encode(packet(1, instruction::kStatus, {0x00}));
  corrupt[8] ^= 0x01;  // a flipped bit in the error byte
  const Bytes last = encode(packet(2, instruction::kPing, {}));
  Bytes stream{0x00, 0xFF, 0x13};  // line noise before the first header
  for (const Bytes* part : std::vector<const Bytes*>{&first, &corrupt, &last})
    stream.insert(stream.end(), part->begin(), part->end());

  PacketParser parser;
  std::vector<PacketParser::Result> results;
  for (std::uint8_t byte : stream) {  // one byte at a time, as a slow serial line delivers them
    parser.feed(&byte, 1);
    while (auto r = parser.next()) results.push_back(*r);
  }
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].kind, PacketParser::Result::Kind::kPacket);
  EXPECT_EQ(readLittleEndian(&results[0].packet.params[1], 4), 166u);
  EXPECT_EQ(results[1].kind, PacketParser::Result::Kind::kCrcError);
  EXPECT_EQ(results[2].kind, PacketParser::Result::Kind::kPacket);
  EXPECT_EQ(results[2].packet.id, 2);
}

TEST(DynamixelProtocol, RefusesALengthTooShortForACrc) {
  const Bytes bad{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x01, 0x00, 0x55};
  PacketParser parser;
  parser.feed(bad.data(), bad.size());
  const auto result = parser.next();
  ASSERT_TRUE(result);
  EXPECT_EQ(result->kind, PacketParser::Result::Kind::kMalformed);
}

TEST(DynamixelControlTable, ConvertsUnitsAndNamesErrors) {
  const Model* xm430 = modelByName("XM430-W350");
  ASSERT_NE(xm430, nullptr);
  EXPECT_EQ(xm430->number, 1020);
  EXPECT_EQ(modelByNumber(1060)->name, "XL430-W250");
  // 0.229 rev/min per unit: 100 units = 22.9 rev/min = 2.398 rad/s.
  EXPECT_NEAR(radiansPerSecond(*xm430, 100), 22.9 * 2 * M_PI / 60, 1e-12);
  EXPECT_EQ(velocityUnits(*xm430, radiansPerSecond(*xm430, -123)), -123);
  EXPECT_NEAR(radians(*xm430, 4096), 2 * M_PI, 1e-12);
  EXPECT_EQ(hardwareErrorText(0x24), "overheating, overload");
  EXPECT_EQ(hardwareErrorText(0), "");
  EXPECT_EQ(processingErrorText(kAlertBit | 3), "CRC error (the servo received a corrupted packet)");
}

}  // namespace
}  // namespace uampc::dynamixel
