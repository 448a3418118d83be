// Tests of the PNG writer and the depth colouring of the panorama snapshots. The PNG is decoded by
// Python's zlib (an independent implementation): chunk CRCs, the zlib stream and every pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "test_directory.hpp"
#include "uampc/evaluator/depth_colouring.hpp"
#include "uampc/evaluator/png_image.hpp"

namespace uampc::evaluator {
namespace {

// Decodes an 8-bit RGB PNG without filters and compares its pixels with the expected bytes (a file).
constexpr const char* kDecode = R"(
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "signature"
at, chunks = 8, []
while at < len(data):
    n, kind = struct.unpack(">I4s", data[at:at + 8])
    body = data[at + 8:at + 8 + n]
    assert struct.unpack(">I", data[at + 8 + n:at + 12 + n])[0] == zlib.crc32(kind + body), kind
    chunks.append((kind, body)); at += 12 + n
assert [k for k, _ in chunks] == [b"IHDR", b"IDAT", b"IEND"], chunks
w, h, depth, colour = struct.unpack(">IIBB", chunks[0][1][:10])
assert (w, h, depth, colour) == (int(sys.argv[2]), int(sys.argv[3]), 8, 2)
raw = zlib.decompress(chunks[1][1])
rows = [raw[y * (3 * w + 1):(y + 1) * (3 * w + 1)] for y in range(h)]
assert all(r[0] == 0 for r in rows), "filter"
assert b"".join(r[1:] for r in rows) == open(sys.argv[4], "rb").read(), "pixels"
)";

int decodeWithPython(const std::string& path, const RgbImage& image) {
  const std::string script_path = path + ".py", expected_path = path + ".rgb";
  std::ofstream(script_path) << kDecode;
  std::ofstream(expected_path, std::ios::binary)
      .write(reinterpret_cast<const char*>(image.rgb.data()), static_cast<std::streamsize>(image.rgb.size()));
  const std::string command = "python3 " + script_path + " " + path + " " + std::to_string(image.width) + " " +
                              std::to_string(image.height) + " " + expected_path;
  return std::system(command.c_str());
}

// The bytes our own stored-deflate encoder wrote before zlib encoded the stream: the same files.
TEST(Png, TheSameBytesAsBeforeZlib) {
  RgbImage image{2, 1, {255, 0, 0, 0, 0, 255}};
  // Python's zlib and struct, writing stored blocks as our encoder did: 0x78 0x01, one final block.
  const std::vector<std::uint8_t> expected = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
      0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x7b, 0x40, 0xe8, 0xdd, 0x00, 0x00, 0x00,
      0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0x01, 0x01, 0x07, 0x00, 0xf8, 0xff, 0x00, 0xff, 0x00, 0x00, 0x00, 0x00,
      0xff, 0x07, 0x00, 0x01, 0xff, 0x55, 0x36, 0xba, 0xc7, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae,
      0x42, 0x60, 0x82};
  EXPECT_EQ(encodePng(image), expected);
}

TEST(Png, SmallImageDecodesPixelForPixel) {
  test::TestDirectory directory;
  RgbImage image{3, 2, {}};
  for (int i = 0; i < 18; ++i) image.rgb.push_back(static_cast<std::uint8_t>(i * 14));
  const std::string path = directory.file("small.png");
  writePng(path, image);
  EXPECT_EQ(decodeWithPython(path, image), 0);
}

TEST(Png, ImageLargerThanOneStoredBlockDecodes) {
  test::TestDirectory directory;
  RgbImage image{200, 120, {}};  // 72,120 bytes of scanlines: two deflate blocks
  for (int i = 0; i < 200 * 120 * 3; ++i) image.rgb.push_back(static_cast<std::uint8_t>((i * 7) % 251));
  const std::string path = directory.file("large.png");
  writePng(path, image);
  EXPECT_EQ(decodeWithPython(path, image), 0);
}

TEST(Png, RejectsWrongSizeAndUnwritablePath) {
  EXPECT_THROW(encodePng(RgbImage{2, 2, std::vector<std::uint8_t>(11)}), std::invalid_argument);
  EXPECT_THROW(encodePng(RgbImage{0, 0, {}}), std::invalid_argument);
  EXPECT_THROW(writePng("/nonexistent-directory/x.png", RgbImage{1, 1, {0, 0, 0}}), std::runtime_error);
}

TEST(DepthColouring, EmptyIsBlackNearIsBrighterThanFar) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const RgbImage image = colourDepth({0.0F, nan, 1.0F, 39.0F, 100.0F, -2.0F}, 3, 2, 40.0);
  auto pixel = [&](int i) { return std::vector<int>(image.rgb.begin() + 3 * i, image.rgb.begin() + 3 * i + 3); };
  EXPECT_EQ(pixel(0), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(pixel(1), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(pixel(5), (std::vector<int>{0, 0, 0}));
  auto brightness = [&](int i) { return pixel(i)[0] + pixel(i)[1] + pixel(i)[2]; };
  EXPECT_GT(brightness(2), brightness(3));
  EXPECT_EQ(pixel(4), (std::vector<int>{68, 1, 84}));  // beyond the range: the far end of the scale
  EXPECT_THROW(colourDepth({1.0F}, 2, 1, 40.0), std::invalid_argument);
  EXPECT_THROW(colourDepth({1.0F}, 1, 1, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace uampc::evaluator
