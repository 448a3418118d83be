// PCD writing (savePointsPcd in map_io.hpp; docs/decisions/pcd-own-reader.md): fields x, y, z as
// float, with the header PCL writes, so that PCL reads our files as it reads its own.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "lzf.hpp"
#include "uampc/run_files/text_file.hpp"
#include "uampc/world/map_io.hpp"

namespace uampc::world {
namespace {

std::string pcdHeaderFor(std::size_t points, const char* data) {
  const std::string n = std::to_string(points);
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
         "COUNT 1 1 1\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA " + data + "\n";
}

// The shortest text that reads back as the same float (also through PCL's atof-then-round).
void appendShortest(std::string& out, float value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  out.append(text, result.ptr);
}

std::string asciiRows(const std::vector<Eigen::Vector3f>& points) {
  std::string out;
  out.reserve(points.size() * 30);
  for (const auto& p : points) {
    appendShortest(out, p.x());
    out += ' ';
    appendShortest(out, p.y());
    out += ' ';
    appendShortest(out, p.z());
    out += '\n';
  }
  return out;
}

// x, y, z of each point in turn, in x86 byte order.
std::string binaryPoints(const std::vector<Eigen::Vector3f>& points) {
  std::string out(points.size() * 12, '\0');
  for (std::size_t i = 0; i < points.size(); ++i) std::memcpy(&out[i * 12], points[i].data(), 12);
  return out;
}

// All x, then all y, then all z, LZF-compressed after the two sizes (compressed, uncompressed).
std::string compressedPoints(const std::string& path, const std::vector<Eigen::Vector3f>& points) {
  if (points.size() * 12 > UINT32_MAX) throw std::runtime_error(path + ": too many points for a binary_compressed PCD");
  std::string fields(points.size() * 12, '\0');
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) std::memcpy(&fields[(a * points.size() + i) * 4], &points[i][a], 4);
  }
  const std::string compressed = lzfCompress(fields);
  const std::uint32_t sizes[2] = {static_cast<std::uint32_t>(compressed.size()), static_cast<std::uint32_t>(fields.size())};
  return std::string(reinterpret_cast<const char*>(sizes), 8) + compressed;
}

}  // namespace

void savePointsPcd(const std::string& path, const std::vector<Eigen::Vector3f>& points, PcdEncoding encoding) {
  if (points.empty()) throw std::runtime_error(path + ": cannot write PCD file of no points");
  std::string body;
  const char* data = "binary";
  switch (encoding) {
    case PcdEncoding::kAscii:
      body = asciiRows(points);
      data = "ascii";
      break;
    case PcdEncoding::kBinary:
      body = binaryPoints(points);
      break;
    case PcdEncoding::kBinaryCompressed:
      body = compressedPoints(path, points);
      data = "binary_compressed";
      break;
  }
  run_files::writeTextFile(path, pcdHeaderFor(points.size(), data) + body);  // whole or absent
}

}  // namespace uampc::world
