#include "uampc/world/map_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "temp_dir.hpp"
#include "uampc/world/seeded_random.hpp"

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
