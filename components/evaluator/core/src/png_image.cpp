#include "uampc/evaluator/png_image.hpp"

#include <zlib.h>

#include <stdexcept>

#include "uampc/run_files/text_file.hpp"

namespace uampc::evaluator {

namespace {

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

// length, type, data, CRC over type and data (PNG specification, section 5.3).
void putChunk(std::vector<std::uint8_t>& out, const char type[4], const std::vector<std::uint8_t>& data) {
  putU32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  putU32(out, static_cast<std::uint32_t>(::crc32(0L, out.data() + type_at, static_cast<uInt>(4 + data.size()))));
}

// The scanlines as a zlib stream (RFC 1950) by zlib itself. Level 0 (stored blocks) keeps the files
// byte for byte what our own encoder wrote before zlib did it; a higher level would make them
// smaller (docs/decisions/zlib-for-checksums-and-png.md).
std::vector<std::uint8_t> zlibStream(const std::vector<std::uint8_t>& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<std::uint8_t> out(size);
  if (compress2(out.data(), &size, raw.data(), static_cast<uLong>(raw.size()), Z_NO_COMPRESSION) != Z_OK) {
    throw std::runtime_error("encodePng: zlib could not compress " + std::to_string(raw.size()) + " bytes");
  }
  out.resize(size);
  return out;
}

}  // namespace

std::vector<std::uint8_t> encodePng(const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    throw std::invalid_argument("encodePng: " + std::to_string(image.rgb.size()) + " bytes for a " +
                                std::to_string(image.width) + " x " + std::to_string(image.height) + " RGB image");
  }
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> header;
  putU32(header, static_cast<std::uint32_t>(image.width));
  putU32(header, static_cast<std::uint32_t>(image.height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, adaptive filters, no interlace
  putChunk(out, "IHDR", header);
  // Each scanline starts with its filter type; 0 = none.
  const std::size_t row_bytes = static_cast<std::size_t>(image.width) * 3;
  std::vector<std::uint8_t> raw;
  raw.reserve((row_bytes + 1) * image.height);
  for (int y = 0; y < image.height; ++y) {
    raw.push_back(0);
    const auto row = image.rgb.begin() + static_cast<std::ptrdiff_t>(y * row_bytes);
    raw.insert(raw.end(), row, row + static_cast<std::ptrdiff_t>(row_bytes));
  }
  putChunk(out, "IDAT", zlibStream(raw));
  putChunk(out, "IEND", {});
  return out;
}

void writePng(const std::string& path, const RgbImage& image) {
  const std::vector<std::uint8_t> bytes = encodePng(image);
  // Whole or absent: a snapshot cut by a full disk is not left looking like one.
  run_files::writeTextFile(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace uampc::evaluator
