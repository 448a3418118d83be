// Map files. The one file that includes PCL (slow to compile, so nothing else should): PCD is
// decoded by PCL after checking the file here; PLY is read by our own reader (ply_reader.cpp).
#include "uampc/world/map_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ply_reader.hpp"
#include "uampc/world/coordinate_bound.hpp"
#include "uampc/world/point_sampling.hpp"

namespace uampc::world {
namespace {

// The largest map read (1.2 GB as x, y, z floats; more than any map a scene needs).
constexpr std::size_t kMaxMapPoints = 100'000'000;
// LZF's best compression: 264 bytes from a 3-byte back reference.
constexpr std::size_t kMaxLzfRatio = 88;

std::string extensionOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool hasXyz(const pcl::PCLPointCloud2& cloud) {
  auto has = [&](const char* name) {
    return std::any_of(cloud.fields.begin(), cloud.fields.end(),
                       [&](const pcl::PCLPointField& f) { return f.name == name; });
  };
  return has("x") && has("y") && has("z");
}

// Points of a PCLPointCloud2; non-finite ones are replaced by NaN so indices stay valid.
std::vector<Eigen::Vector3f> toPoints(const pcl::PCLPointCloud2& cloud, const std::string& path) {
  if (!hasXyz(cloud)) throw std::runtime_error(path + ": has no x, y, z fields");
  const std::size_t declared = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (declared * cloud.point_step > cloud.data.size()) {
    throw std::runtime_error(path + ": declares " + std::to_string(declared) + " points but holds data for fewer");
  }
  // PCL 1.13's conversion takes &points[0] of an empty cloud (undefined behaviour, UBSan stops it).
  if (declared == 0) return {};
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::fromPCLPointCloud2(cloud, xyz);
  std::vector<Eigen::Vector3f> points;
  points.reserve(xyz.size());
  for (const auto& p : xyz.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

void keepFinitePoints(std::vector<Eigen::Vector3f>& points, LoadedMap& map) {
  const auto end =
      std::remove_if(points.begin(), points.end(), [](const Eigen::Vector3f& p) { return !p.allFinite(); });
  const auto skipped = static_cast<std::size_t>(points.end() - end);
  points.erase(end, points.end());
  if (skipped > 0) {
    map.skipped_points += skipped;
    map.warnings.push_back(std::to_string(skipped) + " non-finite points skipped");
  }
}

// PCL's PCD reader trusts the file (pcl 1.13 crashes on some corrupt headers and data), so the
// whole file is checked here before PCL decodes it.
struct PcdLayout {
  std::size_t point_step = 0;  // bytes per point
  std::size_t values = 0;      // values per point (sum of COUNT)
  std::size_t points = 0;
  std::string data;  // ascii, binary, binary_compressed
  std::size_t header_bytes = 0;
};

bool parseCount(const std::string& word, std::size_t& value) {
  if (word.empty() || word.size() > 12 || word.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  value = std::stoull(word);
  return true;
}

// PCL's header reader does not stop at DATA: it goes on reading lines (empty ones and comments
// skipped) for as long as their first word starts with a header keyword, and acts on them. Binary
// data whose first line reads "POINTS 357913941" made it allocate 4 GB. This finds the first such
// line after `pos`, as PCL 1.13 would read it; empty if PCL stops at once. PCL skips only lines
// that are empty; one of blanks ends its header.
std::string headerLineInData(const std::string& bytes, std::size_t pos) {
  static const char* const kKeywords[] = {"FIELDS", "COLUMNS", "SIZE",  "TYPE", "COUNT",
                                          "WIDTH",  "HEIGHT",  "VIEWPOINT", "POINTS", "DATA"};
  while (pos < bytes.size()) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos) eol = bytes.size();
    const std::string line = bytes.substr(pos, std::min<std::size_t>(eol - pos, 4096));
    pos = eol + 1;
    if (line.empty()) continue;
    std::istringstream in(line);
    std::string word;
    if (!(in >> word)) return {};
    if (word[0] == '#' || word.rfind("VERSION", 0) == 0) continue;
    for (const char* keyword : kKeywords) {
      if (word.rfind(keyword, 0) == 0) return keyword;
    }
    return {};
  }
  return {};
}

// The header's lines up to DATA, as written: what checkPcd checks next.
struct PcdHeader {
  std::vector<std::string> sizes, types, counts;
  std::size_t fields = 0, width = 0, height = 0;
  bool have_width = false, have_height = false, have_points = false;
};

using BadPcd = std::function<std::runtime_error(const std::string&)>;

// Reads the header's lines into header and layout (points, data, header_bytes).
void readPcdHeader(const std::string& bytes, const BadPcd& bad, PcdHeader& header, PcdLayout& layout) {
  std::size_t pos = 0, line_number = 0;
  while (layout.data.empty()) {
    const std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos || eol - pos > 4096) throw bad("header has no DATA line");
    std::string line = bytes.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_number;
    // Read as PCL reads it, or PCL decodes another header than the one checked here: PCL skips
    // empty lines only, stops its header at a line of blanks (a fuzzed file then crashed it), and
    // splits words at spaces, tabs and carriage returns only.
    if (line.empty()) continue;
    if (line.find_first_of("\v\f") != std::string::npos) {
      throw bad("header line " + std::to_string(line_number) + " has a vertical tab or form feed");
    }
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      throw bad("header line " + std::to_string(line_number) + " is blank before DATA (PCL ends the header there)");
    }
    if (line.back() == '\r') line.pop_back();
    std::istringstream in(line);
    std::string key;
    in >> key;
    std::vector<std::string> w;
    for (std::string x; in >> x;) w.push_back(x);
    if (key[0] == '#') continue;
    if (key == "VERSION") continue;
    if (key == "FIELDS")
      header.fields = w.size();
    else if (key == "SIZE")
      header.sizes = w;
    else if (key == "TYPE")
      header.types = w;
    else if (key == "COUNT")
      header.counts = w;
    else if (key == "WIDTH")
      header.have_width = w.size() == 1 && parseCount(w[0], header.width);
    else if (key == "HEIGHT")
      header.have_height = w.size() == 1 && parseCount(w[0], header.height);
    else if (key == "POINTS")
      header.have_points = w.size() == 1 && parseCount(w[0], layout.points);
    else if (key == "VIEWPOINT") {
      if (w.size() != 7) throw bad("VIEWPOINT needs 7 numbers");
    } else if (key == "DATA") {
      if (w.size() != 1 || (w[0] != "ascii" && w[0] != "binary" && w[0] != "binary_compressed")) {
        throw bad("unknown DATA kind");
      }
      layout.data = w[0];
    } else {
      throw bad("unknown header line '" + line.substr(0, 40) + "'");
    }
  }
  layout.header_bytes = pos;
}

// FIELDS, SIZE, TYPE, COUNT and the point count agree; fills the layout's point_step and values.
void checkPcdFields(const PcdHeader& header, const BadPcd& bad, PcdLayout& layout) {
  const std::size_t fields = header.fields;
  if (fields == 0 || header.sizes.size() != fields || header.types.size() != fields ||
      (!header.counts.empty() && header.counts.size() != fields)) {
    throw bad("FIELDS, SIZE, TYPE and COUNT disagree");
  }
  if (!header.have_width || !header.have_height || !header.have_points || header.height == 0 ||
      header.width * header.height != layout.points) {
    throw bad("WIDTH, HEIGHT and POINTS missing or inconsistent");
  }
  for (std::size_t i = 0; i < fields; ++i) {
    std::size_t size = 0, count = 1;
    if (!parseCount(header.sizes[i], size) || (size != 1 && size != 2 && size != 4 && size != 8)) {
      throw bad("bad SIZE");
    }
    if (header.types[i] != "I" && header.types[i] != "U" && (header.types[i] != "F" || size < 4)) throw bad("bad TYPE");
    if (!header.counts.empty() && (!parseCount(header.counts[i], count) || count == 0 || count > 4096)) {
      throw bad("bad COUNT");
    }
    layout.point_step += size * count;
    layout.values += count;
  }
}

// The data after the header holds what the header declares, within the memory budget.
void checkPcdPayload(const std::string& bytes, const BadPcd& bad, const PcdLayout& layout) {
  // A memory budget checked before anything is allocated: PCL holds a map two or three times over
  // while it converts it.
  if (layout.points > kMaxMapPoints) {
    throw bad(std::to_string(layout.points) + " points declared; maps of at most " + std::to_string(kMaxMapPoints) +
              " points are read");
  }
  const std::size_t payload = bytes.size() - layout.header_bytes;
  const std::size_t expected = layout.points * layout.point_step;
  if (layout.data == "binary" && payload < expected) throw bad("file shorter than its points");
  if (layout.data == "binary_compressed") {
    std::uint32_t sizes_word[2] = {0, 0};
    if (payload < 8) throw bad("compressed data missing");
    std::memcpy(sizes_word, bytes.data() + layout.header_bytes, 8);
    if (sizes_word[1] != expected || sizes_word[0] > payload - 8) {
      throw bad("compressed data sizes inconsistent");
    }
    // LZF encodes at most 264 bytes in a 3-byte back reference: a file claiming more than that
    // ratio lies about its size (a 171-byte file declaring 4.3 GB took 8.4 GB before it failed).
    if (expected > std::size_t{kMaxLzfRatio} * sizes_word[0]) {
      throw bad("declares " + std::to_string(expected) + " bytes of points in " + std::to_string(sizes_word[0]) +
                " compressed bytes, more than LZF can expand to");
    }
  }
}

// ASCII data: every row of numbers, as many as a point has values, and as many rows as POINTS.
void checkPcdAsciiRows(const std::string& bytes, const BadPcd& bad, const PcdLayout& layout) {
  std::istringstream in(bytes.substr(layout.header_bytes));
  std::string line;
  std::size_t rows = 0;
  while (rows < layout.points && std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t n = 0;
    for (std::string token; row >> token; ++n) {
      char* end = nullptr;
      std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size()) {
        throw bad("data row " + std::to_string(rows + 1) + ": '" + token + "' is not a number");
      }
    }
    if (n == 0) continue;
    if (n != layout.values) {
      throw bad("data row " + std::to_string(rows + 1) + " has " + std::to_string(n) + " values, expected " +
                std::to_string(layout.values));
    }
    ++rows;
  }
  if (rows < layout.points) throw bad("fewer data rows than POINTS");
}

PcdLayout checkPcd(const std::string& path, const std::string& bytes) {
  const BadPcd bad = [&](const std::string& what) { return std::runtime_error(path + ": not a valid PCD file: " + what); };
  PcdHeader header;
  PcdLayout layout;
  readPcdHeader(bytes, bad, header, layout);
  if (const std::string keyword = headerLineInData(bytes, layout.header_bytes); !keyword.empty()) {
    throw bad("the data after DATA starts with a line PCL reads as the header line '" + keyword + " ...'");
  }
  checkPcdFields(header, bad, layout);
  checkPcdPayload(bytes, bad, layout);
  if (layout.data == "ascii") checkPcdAsciiRows(bytes, bad, layout);
  return layout;
}

// The file line of an ASCII PCD's point `index`, counting data rows as checkPcdAsciiRows does
// (lines without a value skipped).
std::size_t asciiPcdLine(const std::string& bytes, std::size_t header_bytes, std::size_t index) {
  std::size_t line = static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + header_bytes, '\n'));
  std::istringstream in(bytes.substr(header_bytes));
  std::size_t row = 0;
  for (std::string text; std::getline(in, text);) {
    ++line;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (row++ == index) break;
  }
  return line;
}

// Refuses the first finite point beyond the coordinate bound (coordinate_bound.hpp), by its line
// in an ASCII file, by its index in a binary one. Indices are the file's: toPoints keeps them.
void checkPcdCoordinates(const std::vector<Eigen::Vector3f>& points, const std::string& path,
                         const std::string& bytes, const PcdLayout& layout) {
  const auto beyond =
      std::find_if(points.begin(), points.end(), [](const Eigen::Vector3f& p) { return !withinCoordinateBound(p); });
  if (beyond == points.end()) return;
  const auto index = static_cast<std::size_t>(beyond - points.begin());
  const std::string where = layout.data == "ascii"
                                ? path + ":" + std::to_string(asciiPcdLine(bytes, layout.header_bytes, index)) + ": point "
                                : path + ": point " + std::to_string(index) + " (counted from 0) ";
  throw std::runtime_error(where + beyondBoundText(*beyond));
}

void loadPcd(const std::string& path, LoadedMap& map) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const PcdLayout layout = checkPcd(path, bytes);
  pcl::PCLPointCloud2 cloud;
  if (pcl::io::loadPCDFile(path, cloud) < 0) {
    throw std::runtime_error(path + ": not a readable PCD file");
  }
  map.points = toPoints(cloud, path);
  checkPcdCoordinates(map.points, path, bytes, layout);
  keepFinitePoints(map.points, map);
}

void loadPly(const std::string& path, LoadedMap& map) {
  PlyContents ply = readPly(path);
  if (ply.faces.empty()) {
    map.points = std::move(ply.vertices);
    keepFinitePoints(map.points, map);
    return;
  }
  // A mesh: vertices stay in place (indices!), bad ones only disqualify their triangles.
  std::vector<Eigen::Vector3f>& vertices = ply.vertices;
  std::size_t bad_vertices = 0;
  for (const auto& v : vertices) bad_vertices += v.allFinite() ? 0 : 1;
  std::size_t bad_triangles = 0;
  const auto n = static_cast<std::uint32_t>(vertices.size());
  for (const auto& idx : ply.faces) {
    if (idx.size() < 3) {
      ++bad_triangles;
      continue;
    }
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) {  // fan
      const std::uint32_t a = idx[0], b = idx[k], c = idx[k + 1];
      if (a >= n || b >= n || c >= n || !vertices[a].allFinite() || !vertices[b].allFinite() ||
          !vertices[c].allFinite()) {
        ++bad_triangles;
        continue;
      }
      map.mesh.triangles.emplace_back(a, b, c);
    }
  }
  for (auto& v : vertices) {
    if (!v.allFinite()) v.setZero();  // used by no kept triangle
  }
  map.mesh.vertices = std::move(vertices);
  if (bad_vertices > 0) {
    map.skipped_points = bad_vertices;
    map.warnings.push_back(std::to_string(bad_vertices) + " non-finite vertices");
  }
  if (bad_triangles > 0) {
    map.skipped_triangles = bad_triangles;
    map.warnings.push_back(std::to_string(bad_triangles) +
                           " faces dropped (bad vertex, index out of range, or fewer than 3)");
  }
}

}  // namespace

LoadedMap loadMap(const std::string& path, const MapLoadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error(path + ": no such map file");
  }
  if (std::filesystem::file_size(path, ec) == 0) throw std::runtime_error(path + ": empty file");
  if (!withinCoordinateBound(options.offset)) {
    throw std::runtime_error(path + ": the map's offset " + beyondBoundText(options.offset));
  }
  LoadedMap map;
  const std::string ext = extensionOf(path);
  try {
    if (ext == ".pcd") {
      loadPcd(path, map);
    } else if (ext == ".ply") {
      loadPly(path, map);
    } else {
      throw std::runtime_error(path + ": unknown map format '" + ext + "' (expected .pcd or .ply)");
    }
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::exception& e) {  // PCL's own exceptions, bad_alloc on absurd headers, ...
    throw std::runtime_error(path + ": cannot read map: " + e.what());
  }
  if (map.mesh.empty() && map.points.empty()) {
    throw std::runtime_error(path + ": map holds no usable points or triangles");
  }
  map.points = voxelDownsample(map.points, options.voxel_size);
  for (auto& p : map.points) p += options.offset;
  for (auto& v : map.mesh.vertices) v += options.offset;
  return map;
}

void savePointsPcd(const std::string& path, const std::vector<Eigen::Vector3f>& points, PcdEncoding encoding) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(points.size());
  for (const auto& p : points) cloud.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  int result = -1;
  if (!cloud.empty()) {
    switch (encoding) {
      case PcdEncoding::kAscii:
        result = pcl::io::savePCDFileASCII(path, cloud);
        break;
      case PcdEncoding::kBinary:
        result = pcl::io::savePCDFileBinary(path, cloud);
        break;
      case PcdEncoding::kBinaryCompressed:
        result = pcl::io::savePCDFileBinaryCompressed(path, cloud);
        break;
    }
  }
  if (result < 0) {
    throw std::runtime_error(path + ": cannot write PCD file");
  }
}

void saveMeshPly(const std::string& path, const TriangleMesh& mesh) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write PLY file");
  out << "ply\nformat ascii 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  out.precision(9);
  for (const auto& v : mesh.vertices) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : mesh.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  if (!out) throw std::runtime_error(path + ": error while writing PLY file");
}

}  // namespace uampc::world
