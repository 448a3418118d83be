// A minimal PNG writer (8-bit RGB, stored deflate blocks, chunk CRCs and the zlib stream by zlib)
// for the report's panorama snapshots: browsers open PNG, not PGM. 180 x 90 pixels take 49 kB.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uampc::evaluator {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel, top row first
};

// The PNG file's bytes. Throws std::invalid_argument if rgb does not hold width * height pixels.
std::vector<std::uint8_t> encodePng(const RgbImage& image);

// Writes encodePng(image) to path; throws std::runtime_error naming the path if it cannot.
void writePng(const std::string& path, const RgbImage& image);

}  // namespace uampc::evaluator
