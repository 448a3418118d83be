#include "../src/lzf.hpp"

#include <gtest/gtest.h>

#include <string>

#include "uampc/world/seeded_random.hpp"

namespace uampc::world {
namespace {

std::string decompressed(const std::string& compressed, std::size_t size) {
  std::string out(size, '\0');
  lzfDecompress(compressed, out.data(), out.size());
  return out;
}

void expectLzfError(const std::string& compressed, std::size_t size, const std::string& fragment) {
  std::string out(size, '\0');
  try {
    lzfDecompress(compressed, out.data(), out.size());
    ADD_FAILURE() << "decompressed, expected an error containing '" << fragment << "'";
  } catch (const LzfError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Lzf, RoundTripsRandomRepetitiveAndEmptyData) {
  SeededRandom random(3);
  std::string noise(5000, '\0'), repeats, mixed;
  for (auto& c : noise) c = static_cast<char>(random.integer(0, 255));
  for (int i = 0; i < 20000; ++i) repeats += static_cast<char>("abcab"[i % 5]);
  for (int i = 0; i < 30000; ++i) mixed += static_cast<char>(i % 700 < 350 ? random.integer(0, 3) : i % 11);
  for (const std::string& data : {noise, repeats, mixed, std::string(), std::string("ab"), std::string(70000, 'z')}) {
    const std::string compressed = lzfCompress(data);
    EXPECT_EQ(decompressed(compressed, data.size()), data);
    EXPECT_LE(compressed.size(), data.size() + data.size() / 32 + 1);
  }
  // Repeats are back references: 20000 bytes of a 5-byte pattern take 76 references of 264.
  EXPECT_LT(lzfCompress(repeats).size(), 250u);
}

TEST(Lzf, ReferencesOfEveryLengthAndDistanceDecode) {
  // A literal run of 8 bytes, then a reference 1 back (repeats the last byte 3 times), one of 9
  // bytes (length field 7 + extra byte 0), and one of 264 from 8 back (the longest).
  std::string c = std::string(1, '\x07') + "abcdefgh";
  c += std::string(1, '\x20') + std::string(1, '\x00');                          // length 3, distance 1
  c += std::string(1, '\xe0') + std::string(1, '\x00') + std::string(1, '\x07');  // length 9, distance 8
  c += std::string(1, '\xe0') + std::string(1, '\xff') + std::string(1, '\x07');  // length 264, distance 8
  std::string want = "abcdefgh" + std::string(3, 'h');
  for (int k = 0; k < 9 + 264; ++k) want += want[want.size() - 8];
  EXPECT_EQ(decompressed(c, want.size()), want);
}

TEST(Lzf, CorruptDataIsRefusedWithoutWritingPastTheOutput) {
  expectLzfError(std::string(1, '\x05') + "abc", 6, "ends inside a literal run");
  expectLzfError(std::string(1, '\x00') + "a" + std::string(1, '\x20'), 4, "ends inside a back reference");
  expectLzfError(std::string(1, '\x00') + "a" + std::string(1, '\xe0'), 12, "ends inside a back reference's length");
  expectLzfError(std::string(1, '\x00') + "a" + std::string(1, '\x20') + std::string(1, '\x01'), 4,
                 "points before the start");
  expectLzfError(std::string(1, '\x03') + "abcd", 3, "expands beyond its declared 3 bytes");
  expectLzfError(std::string(1, '\x00') + "a" + std::string(1, '\xe0') + std::string(1, '\xff') + std::string(1, '\x00'),
                 100, "expands beyond its declared 100 bytes");
  expectLzfError(std::string(1, '\x01') + "ab", 3, "expands to 2 bytes, not the declared 3");
  expectLzfError("", 1, "expands to 0 bytes");
}

}  // namespace
}  // namespace uampc::world
