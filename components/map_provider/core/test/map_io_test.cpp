#include "uampc/world/map_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>

#include "../src/lzf.hpp"
#include "full_disk.hpp"
#include "temp_dir.hpp"
#include "uampc/world/seeded_random.hpp"
#include "uampc/world/trajectory_io.hpp"

namespace uampc::world {
namespace {

using test::TempDir;

void expectLoadError(const std::string& path, const std::string& fragment) {
  try {
    loadMap(path);
    ADD_FAILURE() << path << ": loaded, expected an error containing '" << fragment << "'";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path, 0), 0u) << "message does not start with the file: " << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

const char* kAsciiPcdHeader = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

// The writers on a full disk (test::ScopedFileSizeLimit, full_disk.hpp: EFBIG where a disk gives
// ENOSPC): each fails naming the file and the reason, and leaves no file cut short that a later
// load would take for a smaller map (docs/decisions/run-files-whole-or-absent.md).
TEST(MapIo, WritersOnAFullDiskLeaveNoFileCutShort) {
  TempDir dir;
  const std::vector<Eigen::Vector3f> points(1000, Eigen::Vector3f(1, 2, 3));
  TriangleMesh box;
  box.addBox({0, 0, 0}, {1, 1, 1});
  std::vector<TimedPose> poses;
  for (int i = 0; i < 50; ++i) {
    poses.push_back({0.1 * i, Eigen::Vector3d(0.1 * i, 0, 0), Eigen::Quaterniond::Identity()});
  }
  const Trajectory trajectory(poses);
  const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> writers = {
      {"map.pcd", [&](const std::string& path) { savePointsPcd(path, points); }},
      {"ascii.pcd", [&](const std::string& path) { savePointsPcd(path, points, PcdEncoding::kAscii); }},
      {"box.ply", [&](const std::string& path) { saveMeshPly(path, box); }},
      {"path.tum", [&](const std::string& path) { writeTum(path, trajectory); }}};
  for (const auto& [name, write] : writers) {
    const std::string path = dir.file(name);
    {
      uampc::test::ScopedFileSizeLimit full_disk(100);
      try {
        write(path);
        ADD_FAILURE() << name << ": written under a 100-byte limit";
      } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write " + path + ": File too large");
      }
    }
    EXPECT_FALSE(std::ifstream(path).good()) << name << " left cut short";
    write(path);  // with room, whole
    EXPECT_TRUE(std::ifstream(path).good()) << name;
  }
}

TEST(MapIo, PcdRoundTripWithVoxelAndOffset) {
  TempDir dir;
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 100; ++i) points.emplace_back(0.01f * i, 2.0f, 3.0f);
  savePointsPcd(dir.file("line.pcd"), points);
  const LoadedMap plain = loadMap(dir.file("line.pcd"));
  EXPECT_FALSE(plain.isMesh());
  EXPECT_EQ(plain.points, points);
  savePointsPcd(dir.file("ascii.pcd"), points, PcdEncoding::kAscii);
  EXPECT_EQ(loadMap(dir.file("ascii.pcd")).points.size(), points.size());
  MapLoadOptions options;
  options.voxel_size = 0.5;
  options.offset = {10, 0, 0};
  const LoadedMap map = loadMap(dir.file("line.pcd"), options);
  ASSERT_EQ(map.points.size(), 2u);
  EXPECT_NEAR(map.points[0].x(), 10.0f + 0.245f, 1e-4f);
  EXPECT_NEAR(map.points[0].y(), 2.0f, 1e-6f);
}

TEST(MapIo, NonFinitePointsAreSkippedAndCounted) {
  TempDir dir;
  const std::string path = dir.write("nan.pcd", std::string(kAsciiPcdHeader) +
                                                    "WIDTH 4\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
                                                    "1 2 3\nnan 0 0\n4 5 6\n0 inf 0\n");
  const LoadedMap map = loadMap(path);
  EXPECT_EQ(map.points.size(), 2u);
  EXPECT_EQ(map.skipped_points, 2u);
  ASSERT_EQ(map.warnings.size(), 1u);
  EXPECT_NE(map.warnings[0].find("2 non-finite"), std::string::npos);
}

TEST(MapIo, PlyMeshPlyPointsAndBadFaces) {
  TempDir dir;
  TriangleMesh box;
  box.addBox({0, 0, 0}, {1, 2, 3});
  saveMeshPly(dir.file("box.ply"), box);
  const LoadedMap mesh = loadMap(dir.file("box.ply"));
  ASSERT_TRUE(mesh.isMesh());
  EXPECT_EQ(mesh.mesh.size(), 12u);
  EXPECT_NEAR(mesh.mesh.area(), 2 * (2 + 3 + 6), 1e-4);

  const std::string quads =
      dir.write("quads.ply",
                "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0\n1 0 0\n1 1 0\n0 1 0\nnan 0 0\n4 0 1 2 3\n3 0 1 9\n3 0 1 4\n");
  const LoadedMap q = loadMap(quads);
  EXPECT_EQ(q.mesh.size(), 2u);  // the quad as a fan
  EXPECT_EQ(q.skipped_triangles, 2u);
  EXPECT_EQ(q.skipped_points, 1u);
  EXPECT_EQ(q.warnings.size(), 2u);

  const std::string cloud = dir.write("cloud.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nend_header\n0 0 0\n1 0 0\n1 1 0\n");
  const LoadedMap c = loadMap(cloud);
  EXPECT_FALSE(c.isMesh());
  EXPECT_EQ(c.points.size(), 3u);
}

TEST(MapIo, BrokenFilesGiveErrorsNamingTheFile) {
  TempDir dir;
  expectLoadError(dir.file("missing.pcd"), "no such map file");
  expectLoadError(dir.write("empty.pcd", ""), "empty file");
  expectLoadError(dir.write("map.xyz", "1 2 3\n"), "unknown map format");
  expectLoadError(dir.write("garbage.pcd", std::string(4096, '\x7f')), "");
  expectLoadError(dir.write("garbage.ply", "ply\nthis is not a header\n\x01\x02\x03"), "");
  expectLoadError(dir.write("noxyz.pcd",
                            "VERSION 0.7\nFIELDS a b\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\n"
                            "HEIGHT 1\nPOINTS 1\nDATA ascii\n1 2\n"),
                  "");
  expectLoadError(dir.write("zero.pcd", std::string(kAsciiPcdHeader) + "WIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA ascii\n"),
                  "");
  expectLoadError(
      dir.write("allnan.pcd", std::string(kAsciiPcdHeader) + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\nnan 0 0\n"),
      "no usable points");
  // A binary PCD cut short: the header promises more points than the file holds.
  std::vector<Eigen::Vector3f> points(1000, Eigen::Vector3f(1, 2, 3));
  savePointsPcd(dir.file("full.pcd"), points);
  std::ifstream in(dir.file("full.pcd"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  expectLoadError(dir.write("cut.pcd", bytes.substr(0, bytes.size() / 2)), "");
  // binary_compressed PCDs, cut short and with a corrupted size word.
  {
    savePointsPcd(dir.file("c.pcd"), points, PcdEncoding::kBinaryCompressed);
    std::ifstream cin(dir.file("c.pcd"), std::ios::binary);
    std::string c((std::istreambuf_iterator<char>(cin)), std::istreambuf_iterator<char>());
    EXPECT_EQ(loadMap(dir.file("c.pcd")).points.size(), 1000u);
    expectLoadError(dir.write("cutc.pcd", c.substr(0, c.size() - 20)), "");
    const std::size_t data = c.find("DATA binary_compressed\n") + 23;
    std::string big = c;
    big[data + 3] = '\x7f';  // compressed size: huge
    expectLoadError(dir.write("bigc.pcd", big), "");
    std::string wrong = c;
    wrong[data + 4] = '\x01';  // uncompressed size: wrong
    wrong[data + 5] = '\x00';
    wrong[data + 6] = '\x00';
    wrong[data + 7] = '\x00';
    expectLoadError(dir.write("wrongc.pcd", wrong), "");
  }
  // A PLY mesh cut short in its faces.
  TriangleMesh box;
  box.addBox({0, 0, 0}, {1, 1, 1});
  saveMeshPly(dir.file("box.ply"), box);
  std::ifstream ply_in(dir.file("box.ply"));
  const std::string ply((std::istreambuf_iterator<char>(ply_in)), std::istreambuf_iterator<char>());
  expectLoadError(dir.write("cut.ply", ply.substr(0, ply.size() - 40)), "");
}

// Declared sizes beyond the memory budget are refused before anything is allocated (a
// 171-byte binary_compressed PCD declaring 357,913,941 points took 8.4 GB before it failed).
TEST(MapIo, DeclaredSizesBeyondTheBudgetAreRefusedBeforeAllocation) {
  TempDir dir;
  const std::string header = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  // 357,913,941 points of 12 bytes: 4,294,967,292 bytes, which fits the 32-bit size word.
  std::string tiny = header + "WIDTH 357913941\nHEIGHT 1\nPOINTS 357913941\nDATA binary_compressed\n";
  const std::uint32_t sizes[2] = {8, 4294967292u};
  tiny.append(reinterpret_cast<const char*>(sizes), 8);
  tiny.append(8, '\0');
  expectLoadError(dir.write("tiny.pcd", tiny), "357913941 points declared; maps of at most 100000000 points");
  // Within the point budget, but more than LZF can expand its compressed bytes to.
  std::string liar = header + "WIDTH 1000000\nHEIGHT 1\nPOINTS 1000000\nDATA binary_compressed\n";
  const std::uint32_t liar_sizes[2] = {8, 12000000u};
  liar.append(reinterpret_cast<const char*>(liar_sizes), 8);
  liar.append(8, '\0');
  expectLoadError(dir.write("liar.pcd", liar), "more than LZF can expand to");
}

// PCL 1.13 keeps reading header lines after DATA until a line that is not one: binary data whose
// first line reads "POINTS 357913941" made it allocate 4 GB (found by fuzz_pcd in its hour run).
TEST(MapIo, BinaryDataThatReadsAsAHeaderLineIsRefused) {
  TempDir dir;
  const std::string header = "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                             "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA binary\n";
  std::string data = "POINTS\x01\x02 357913941\n";
  data.resize(24, '\0');
  expectLoadError(dir.write("points_in_data.pcd", header + data),
                  "the data after DATA starts with a line PCL reads as the header line 'POINTS");
  // A comment-like line is skipped by PCL, and the one after it read: refused the same way.
  expectLoadError(dir.write("comment_then_width.pcd", header + std::string("#\nWIDTH 9\n") + std::string(13, '\0')),
                  "PCL reads as the header line 'WIDTH");
  // Data that PCL stops at is read as always (two points of zeros, the first byte a '#' or not).
  std::string zeros = header + std::string(24, '\0');
  EXPECT_EQ(loadMap(dir.write("zeros.pcd", zeros), {}).points.size(), 2u);
  // A line of blanks ends PCL's header (it skips empty lines only): PCL then read a header without
  // points and crashed on the data (fuzz_pcd). Refused before PCL sees it.
  expectLoadError(dir.write("blank_line.pcd", "\r \r\n" + header + std::string(24, '\0')),
                  "header line 1 is blank before DATA");
  EXPECT_EQ(loadMap(dir.write("empty_line.pcd", "\n" + header + std::string(24, '\0')), {}).points.size(), 2u);
}

// A PCD field as a test writes it.
struct TestField {
  std::string name;
  char type;  // I, U, F
  int size, count;
};

// A PCD file of `fields` whose points are `rows` (every value of a point, field after field),
// written byte by byte in `data` (ascii, binary, binary_compressed).
std::string testPcd(const std::vector<TestField>& fields, const std::vector<std::vector<double>>& rows,
                    const std::string& data) {
  std::string names, sizes, types, counts;
  for (const auto& f : fields) {
    names += " " + f.name;
    sizes += " " + std::to_string(f.size);
    types += std::string(" ") + f.type;
    counts += " " + std::to_string(f.count);
  }
  const std::string n = std::to_string(rows.size());
  std::string out = "# .PCD v0.7\nVERSION 0.7\nFIELDS" + names + "\nSIZE" + sizes + "\nTYPE" + types + "\nCOUNT" + counts +
                    "\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA " + data + "\n";
  if (data == "ascii") {
    for (const auto& row : rows) {
      for (double v : row) {
        char text[40];
        std::snprintf(text, sizeof text, "%.17g ", v);
        out += text;
      }
      out += "\n";
    }
    return out;
  }
  auto encode = [](const TestField& f, double v) {
    char bytes[8];
    if (f.type == 'F' && f.size == 4) {
      const float x = static_cast<float>(v);
      std::memcpy(bytes, &x, 4);
    } else if (f.type == 'F') {
      std::memcpy(bytes, &v, 8);
    } else {
      const auto i = static_cast<std::int64_t>(v);
      std::memcpy(bytes, &i, 8);  // little-endian: the low f.size bytes are the value
    }
    return std::string(bytes, static_cast<std::size_t>(f.size));
  };
  // Each field's values for each point: [field][point] (binary_compressed stores them so).
  std::vector<std::vector<std::string>> columns(fields.size(), std::vector<std::string>(rows.size()));
  for (std::size_t p = 0; p < rows.size(); ++p) {
    std::size_t v = 0;
    for (std::size_t f = 0; f < fields.size(); ++f) {
      for (int c = 0; c < fields[f].count; ++c) columns[f][p] += encode(fields[f], rows[p][v++]);
    }
  }
  std::string plain;
  if (data == "binary") {
    for (std::size_t p = 0; p < rows.size(); ++p) {
      for (std::size_t f = 0; f < fields.size(); ++f) plain += columns[f][p];
    }
    return out + plain;
  }
  for (const auto& column : columns) {
    for (const auto& value : column) plain += value;
  }
  const std::string compressed = lzfCompress(plain);
  const std::uint32_t sizes_word[2] = {static_cast<std::uint32_t>(compressed.size()),
                                       static_cast<std::uint32_t>(plain.size())};
  return out + std::string(reinterpret_cast<const char*>(sizes_word), 8) + compressed;
}

const char* const kPcdData[] = {"ascii", "binary", "binary_compressed"};

// x, y, z anywhere among other fields (integers, floats, COUNT 3), of SIZE 4 or 8: the other
// fields are skipped by their size, x, y, z read in every encoding.
TEST(MapIo, PcdReadsXyzAmongOtherFieldsOfAnyOrderAndSize) {
  TempDir dir;
  const std::vector<TestField> fields = {{"rgb", 'U', 4, 1}, {"z", 'F', 8, 1},     {"normal", 'F', 4, 3},
                                         {"x", 'F', 4, 1},   {"ring", 'U', 1, 2},  {"y", 'F', 8, 1},
                                         {"t", 'I', 8, 1},   {"_", 'U', 1, 1}};
  std::vector<std::vector<double>> rows;
  std::vector<Eigen::Vector3f> want;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.25 * i, y = 0.1 * i - 7, z = 1e-3 * i * i;
    rows.push_back({255.0 * i, z, 0.5, -0.5, 1.0, x, 3, 200, y, -12345678901.0 * i, 7});
    want.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  }
  for (const char* data : {"ascii", "binary"}) {
    EXPECT_EQ(loadMap(dir.write(std::string(data) + ".pcd", testPcd(fields, rows, data))).points, want) << data;
  }
  // binary_compressed without the padding field (it is refused there, below).
  std::vector<TestField> no_padding = fields;
  no_padding.pop_back();
  for (auto& row : rows) row.pop_back();
  EXPECT_EQ(loadMap(dir.write("compressed.pcd", testPcd(no_padding, rows, "binary_compressed"))).points, want);
}

// PCL 1.13 read x, y, z only as floats of SIZE 4 and COUNT 1, and left a coordinate 0 without one;
// an x of another type is now refused, and of two fields named x the float one is read, as PCL did.
TEST(MapIo, PcdCoordinatesThatAreNotFloatsAreRefused) {
  TempDir dir;
  for (const char* data : kPcdData) {
    const std::string name = std::string(data) + ".pcd";
    expectLoadError(dir.write("int_" + name, testPcd({{"x", 'I', 4, 1}, {"y", 'F', 4, 1}, {"z", 'F', 4, 1}},
                                                     {{1, 2, 3}}, data)),
                    "field x is not a float of COUNT 1");
    expectLoadError(dir.write("count_" + name, testPcd({{"x", 'F', 4, 1}, {"y", 'F', 4, 1}, {"z", 'F', 8, 2}},
                                                       {{1, 2, 3, 4}}, data)),
                    "field z is not a float of COUNT 1");
    expectLoadError(dir.write("noxyz_" + name, testPcd({{"x", 'F', 4, 1}, {"y", 'F', 4, 1}}, {{1, 2}}, data)),
                    "has no x, y, z fields");
    const LoadedMap two_x = loadMap(dir.write(
        "two_x_" + name,
        testPcd({{"x", 'I', 2, 1}, {"x", 'F', 4, 1}, {"y", 'F', 4, 1}, {"z", 'F', 4, 1}}, {{9, 1, 2, 3}}, data)));
    EXPECT_EQ(two_x.points, std::vector<Eigen::Vector3f>{Eigen::Vector3f(1, 2, 3)}) << data;
  }
}

// binary_compressed is bounded: corrupt LZF data, or padding fields whose layout PCL gets wrong,
// stop the load naming the file; a double beyond float's range is refused, not made infinite.
TEST(MapIo, PcdCompressedDataAndDoublesAreCheckedWithTheFileNamed) {
  TempDir dir;
  const std::vector<TestField> xyz = {{"x", 'F', 4, 1}, {"y", 'F', 4, 1}, {"z", 'F', 4, 1}};
  std::string c = testPcd(xyz, {{1, 2, 3}, {4, 5, 6}}, "binary_compressed");
  const std::size_t data = c.find("DATA binary_compressed\n") + 23;
  // 24 bytes declared; a literal byte, then a reference 6 bytes back.
  const std::string before_start = c.substr(0, data) + std::string("\x04\0\0\0\x18\0\0\0", 8) +
                                   std::string("\x00\x01\x20\x05", 4);
  expectLoadError(dir.write("before_start.pcd", before_start),
                  "before_start.pcd: not a valid PCD file: a back reference points before the start of the data");
  const std::string short_data = c.substr(0, data) + std::string("\x02\0\0\0\x18\0\0\0", 8) +
                                 std::string("\x00\x01", 2);
  expectLoadError(dir.write("short.pcd", short_data), "compressed data expands to 1 bytes, not the declared 24");
  expectLoadError(dir.write("padding.pcd", testPcd({{"x", 'F', 4, 1}, {"_", 'U', 4, 1}, {"y", 'F', 4, 1},
                                                    {"z", 'F', 4, 1}},
                                                   {{1, 0, 2, 3}}, "binary_compressed")),
                  "padding field '_'");
  const std::vector<TestField> doubles = {{"x", 'F', 8, 1}, {"y", 'F', 8, 1}, {"z", 'F', 8, 1}};
  for (const char* kind : {"binary", "binary_compressed"}) {
    expectLoadError(dir.write(std::string("huge_") + kind + ".pcd", testPcd(doubles, {{1, 2, 3}, {0, 1e100, 0}}, kind)),
                    "point 1 (counted from 0) is 1e+100 m from the origin");
  }
  expectLoadError(dir.write("huge_ascii.pcd", testPcd(doubles, {{1, 2, 3}, {0, 1e100, 0}}, "ascii")),
                  "huge_ascii.pcd:13: point is 1e+100 m from the origin");
}

// Rows are what the row check reads: lines of blanks skipped, values split at any blank (PCL 1.13
// took a line of blanks for a point at the origin, and a vertical tab for part of a value).
TEST(MapIo, PcdAsciiRowsAreSplitAtBlanksAndBlankLinesSkipped) {
  TempDir dir;
  const std::string path = dir.write("blanks.pcd", std::string(kAsciiPcdHeader) +
                                                       "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n1 2 3\n \t \n"
                                                       "4\v5\f6\r\n\r\n  7\t8 9  \n");
  const std::vector<Eigen::Vector3f> want = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  EXPECT_EQ(loadMap(path).points, want);
}

// ASCII values become the floats PCL 1.13 makes of them: the first through a stream (strtof,
// rounded once), every later one atof's double rounded to float. The two differ for a decimal just
// above halfway between 1 and the next float.
TEST(MapIo, PcdAsciiValuesAreRoundedAsPclRoundsThem) {
  TempDir dir;
  const std::string halfway = "1.00000005960464477550";
  const std::string path = dir.write("halfway.pcd", std::string(kAsciiPcdHeader) +
                                                        "WIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n" + halfway + " " +
                                                        halfway + " 0\n" + halfway + " 0 0\n");
  const std::vector<Eigen::Vector3f> points = loadMap(path).points;
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].x(), std::nextafter(1.0f, 2.0f));
  EXPECT_EQ(points[0].y(), 1.0f);
  EXPECT_EQ(points[1].x(), 1.0f);
}

// What savePointsPcd writes reads back bit for bit in every encoding, whatever the magnitude (a
// zero's sign aside: loadMap adds the map's offset, and -0 + 0 is 0).
TEST(MapIo, PcdWrittenPointsReadBackExactly) {
  TempDir dir;
  SeededRandom random(5);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 3000; ++i) {
    const double scale = std::pow(10.0, random.integer(-40, 5));
    points.emplace_back(static_cast<float>(scale * random.uniform(-1, 1)), static_cast<float>(scale * random.uniform(-1, 1)),
                        static_cast<float>(random.uniform(-1e5, 1e5)));
  }
  points.emplace_back(0.0f, std::numeric_limits<float>::denorm_min(), 999999.94f);
  for (int i = 0; i < 500; ++i) points.push_back(points[i % 7]);  // repeats, for LZF's back references
  for (auto encoding : {PcdEncoding::kAscii, PcdEncoding::kBinary, PcdEncoding::kBinaryCompressed}) {
    savePointsPcd(dir.file("points.pcd"), points, encoding);
    const std::vector<Eigen::Vector3f> read = loadMap(dir.file("points.pcd")).points;
    ASSERT_EQ(read.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_EQ(std::memcmp(read[i].data(), points[i].data(), sizeof(points[i])), 0)
          << "encoding " << static_cast<int>(encoding) << ", point " << i << ": " << read[i].transpose() << " read, "
          << points[i].transpose() << " written";
    }
  }
}

// A binary little-endian PLY of a mesh, written byte by byte (float xyz, uchar count, int index).
std::string binaryPly(const TriangleMesh& mesh) {
  std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(mesh.vertices.size()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(mesh.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
  for (const auto& v : mesh.vertices) put(v.data(), 12);  // x86: little-endian host
  for (const auto& t : mesh.triangles) {
    const unsigned char three = 3;
    put(&three, 1);
    put(t.data(), 12);
  }
  return out;
}

// Map points beyond 1e6 m from the origin are refused when read (a pose at 1e20 m aborted the
// ray-caster inside Embree; docs/user/faults.md): by line in ASCII files, by index in binary ones.
TEST(MapIo, PointsBeyondTheCoordinateBoundAreRefusedWithLineOrIndex) {
  TempDir dir;
  const std::string ascii_pcd = std::string(kAsciiPcdHeader) + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n";
  // Line 13: the header is 10 lines, then a point, an empty line, then the far one.
  expectLoadError(dir.write("far_ascii.pcd", ascii_pcd + "1 2 3\n\n0 1e20 0\n4 5 6\n"),
                  "far_ascii.pcd:13: point is 1e+20 m from the origin, beyond the 1e+06 m");
  std::vector<Eigen::Vector3f> points(5, Eigen::Vector3f(1, 2, 3));
  points[3] = {0, 0, -3e7f};
  savePointsPcd(dir.file("far_binary.pcd"), points);
  expectLoadError(dir.file("far_binary.pcd"), "far_binary.pcd: point 3 (counted from 0) is 3e+07 m from the origin");
  savePointsPcd(dir.file("far_compressed.pcd"), points, PcdEncoding::kBinaryCompressed);
  expectLoadError(dir.file("far_compressed.pcd"), "far_compressed.pcd: point 3 (counted from 0) is 3e+07 m");

  const std::string ply_header =
      "ply\nformat ascii 1.0\ncomment far\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  // Beyond float's range too: refused, not turned into infinity and skipped.
  expectLoadError(dir.write("far_ascii.ply", ply_header + "0 0 0\n1 0 0\n0 0 1e39\n3 0 1 2\n"),
                  "far_ascii.ply:13: vertex 2 (counted from 0) is 1e+39 m from the origin");
  TriangleMesh box;
  box.addBox({0, 0, 0}, {1, 2, 3});
  box.vertices[5].x() = 5e6f;
  expectLoadError(dir.write("far_binary.ply", binaryPly(box)), "far_binary.ply: vertex 5 (counted from 0) is 5e+06 m");

  // Non-finite points are still skipped, points within the bound loaded, and the offset bounded too.
  EXPECT_EQ(loadMap(dir.write("near.pcd", ascii_pcd + "999999 0 0\nnan 0 0\n0 0 1\n")).points.size(), 2u);
  MapLoadOptions far_offset;
  far_offset.offset = {0, 0, 1e20f};
  try {
    loadMap(dir.file("near.pcd"), far_offset);
    ADD_FAILURE() << "a map offset of 1e20 m was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("offset is 1e+20 m from the origin"), std::string::npos) << e.what();
  }
}

TEST(MapIo, BinaryPlyMesh) {
  TempDir dir;
  TriangleMesh box;
  box.addBox({0, 0, 0}, {1, 2, 3});
  const LoadedMap map = loadMap(dir.write("box.ply", binaryPly(box)));
  EXPECT_EQ(map.mesh.triangles, box.triangles);
  EXPECT_EQ(map.mesh.vertices, box.vertices);
}

// Randomly corrupted files (bytes changed, files cut short) load or throw, never crash.
TEST(MapIo, RandomCorruptionNeverCrashes) {
  TempDir dir;
  TriangleMesh mesh;
  mesh.addBox({0, 0, 0}, {1, 2, 3});
  mesh.addCylinder({3, 3, 0}, 1.0f, 2.0f, 8);
  std::vector<std::pair<std::string, std::string>> originals;
  for (auto encoding : {PcdEncoding::kAscii, PcdEncoding::kBinary, PcdEncoding::kBinaryCompressed}) {
    savePointsPcd(dir.file("src.pcd"), mesh.vertices, encoding);
    std::ifstream in(dir.file("src.pcd"), std::ios::binary);
    originals.emplace_back(".pcd", std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
  }
  saveMeshPly(dir.file("src.ply"), mesh);
  std::ifstream in(dir.file("src.ply"), std::ios::binary);
  originals.emplace_back(".ply", std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
  originals.emplace_back(".ply", binaryPly(mesh));

  SeededRandom random(1);
  std::size_t loaded = 0, refused = 0;
  for (const auto& [ext, original] : originals) {
    for (int i = 0; i < 300; ++i) {
      std::string bytes = original;
      for (int k = random.integer(1, 4); k > 0 && !bytes.empty(); --k) {
        const auto at = static_cast<std::size_t>(random.integer(0, static_cast<int>(bytes.size()) - 1));
        switch (random.integer(0, 2)) {
          case 0:
            bytes[at] = static_cast<char>(random.integer(0, 255));
            break;
          case 1:
            bytes.resize(at);
            break;
          default:
            bytes[at] = "0123456789 \n-e."[random.integer(0, 14)];
            break;
        }
      }
      try {
        loadMap(dir.write("fuzz" + ext, bytes));
        ++loaded;
      } catch (const std::runtime_error&) {
        ++refused;
      }
    }
  }
  EXPECT_EQ(loaded + refused, 1500u);
  EXPECT_GT(refused, 500u);
}

}  // namespace
}  // namespace uampc::world
