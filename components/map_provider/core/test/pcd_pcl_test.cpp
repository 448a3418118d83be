// Our PCD reader and writer against PCL 1.13's (docs/decisions/pcd-own-reader.md): PCL reads the
// files we write, we read the files PCL writes, and every PCD file of the repository gives the
// points PCL gives. Only this test links PCL's io library; the shipped libraries do not.
#include <gtest/gtest.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "temp_dir.hpp"
#include "uampc/world/map_io.hpp"
#include "uampc/world/seeded_random.hpp"

namespace uampc::world {
namespace {

using test::TempDir;

// Equal values, or both NaN (a zero's sign aside: loadMap adds the map's offset, and -0 + 0 is 0).
bool sameFloat(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

bool samePoint(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return sameFloat(a.x(), b.x()) && sameFloat(a.y(), b.y()) && sameFloat(a.z(), b.z());
}

void expectSamePoints(const std::vector<Eigen::Vector3f>& got, const std::vector<Eigen::Vector3f>& want,
                      const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_TRUE(samePoint(got[i], want[i])) << what << ": point " << i << " is " << got[i].transpose() << ", not "
                                            << want[i].transpose();
  }
}

std::vector<Eigen::Vector3f> finite(const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector3f> kept;
  for (const auto& p : points) {
    if (p.allFinite()) kept.push_back(p);
  }
  return kept;
}

// x, y, z as PCL 1.13 decodes them: its PCLPointCloud2, then fromPCLPointCloud2 to PointXYZ.
std::vector<Eigen::Vector3f> pclPoints(const std::string& path) {
  pcl::PCLPointCloud2 cloud;
  if (pcl::io::loadPCDFile(path, cloud) < 0) throw std::runtime_error(path + ": PCL cannot read it");
  pcl::PointCloud<pcl::PointXYZ> xyz;
  if (cloud.width * cloud.height > 0) pcl::fromPCLPointCloud2(cloud, xyz);
  std::vector<Eigen::Vector3f> points;
  for (const auto& p : xyz.points) points.emplace_back(p.x, p.y, p.z);
  return points;
}

// x, y, z of SIZE 8 from PCL's decoded data (fromPCLPointCloud2 reads floats only, and left such
// coordinates 0), rounded to float.
std::vector<Eigen::Vector3f> pclDoublePoints(const std::string& path) {
  pcl::PCLPointCloud2 cloud;
  if (pcl::io::loadPCDFile(path, cloud) < 0) throw std::runtime_error(path + ": PCL cannot read it");
  std::size_t offset[3];
  for (int a = 0; a < 3; ++a) offset[a] = cloud.fields[static_cast<std::size_t>(pcl::getFieldIndex(cloud, std::string(1, "xyz"[a])))].offset;
  std::vector<Eigen::Vector3f> points;
  for (std::size_t i = 0; i < std::size_t{cloud.width} * cloud.height; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) std::memcpy(&p[a], &cloud.data[i * cloud.point_step + offset[a]], 8);
    points.push_back(p.cast<float>());
  }
  return points;
}

bool coordinatesAreDoubles(const std::string& path) {
  pcl::PCLPointCloud2 cloud;
  pcl::io::loadPCDFile(path, cloud);
  const int x = pcl::getFieldIndex(cloud, "x");
  return x >= 0 && cloud.fields[static_cast<std::size_t>(x)].datatype == pcl::PCLPointField::FLOAT64;
}

std::vector<Eigen::Vector3f> somePoints() {
  SeededRandom random(11);
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < 2000; ++i) {
    const double scale = std::pow(10.0, random.integer(-12, 5));
    points.emplace_back(static_cast<float>(scale * random.uniform(-1, 1)), static_cast<float>(random.uniform(-500, 500)),
                        static_cast<float>(scale * random.uniform(-1, 1)));
  }
  points.emplace_back(-0.0f, std::numeric_limits<float>::denorm_min(), 1.0f);
  for (int i = 0; i < 300; ++i) points.push_back(points[i % 5]);  // repeats: LZF's back references
  points.emplace_back(std::nanf(""), 1.0f, 2.0f);
  points.emplace_back(3.0f, std::numeric_limits<float>::infinity(), 4.0f);
  return points;
}

const PcdEncoding kEncodings[] = {PcdEncoding::kAscii, PcdEncoding::kBinary, PcdEncoding::kBinaryCompressed};

TEST(PcdAndPcl, PclReadsTheFilesWeWriteExactly) {
  TempDir dir;
  const std::vector<Eigen::Vector3f> points = somePoints();
  for (PcdEncoding encoding : kEncodings) {
    const std::string what = "encoding " + std::to_string(static_cast<int>(encoding));
    savePointsPcd(dir.file("ours.pcd"), points, encoding);
    expectSamePoints(pclPoints(dir.file("ours.pcd")), points, "PCL, " + what);
    expectSamePoints(loadMap(dir.file("ours.pcd")).points, finite(points), "ours, " + what);
  }
}

// Files PCL writes (points of x, y, z only, and with more fields around them) read as PCL reads them.
TEST(PcdAndPcl, WeReadTheFilesPclWritesAsPclReadsThem) {
  TempDir dir;
  const std::vector<Eigen::Vector3f> points = somePoints();
  pcl::PointCloud<pcl::PointXYZ> xyz;
  pcl::PointCloud<pcl::PointXYZRGBNormal> rich;
  for (std::size_t i = 0; i < points.size(); ++i) {
    xyz.push_back(pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z()));
    pcl::PointXYZRGBNormal p;
    p.x = points[i].x();
    p.y = points[i].y();
    p.z = points[i].z();
    p.r = static_cast<std::uint8_t>(i);
    p.normal_x = 0.5f * static_cast<float>(i);
    p.curvature = -1.0f;
    rich.push_back(p);
  }
  const std::string path = dir.file("pcl.pcd");
  auto check = [&](const std::string& what) {
    const std::vector<Eigen::Vector3f> pcl = pclPoints(path);
    ASSERT_EQ(pcl.size(), points.size()) << what;
    expectSamePoints(loadMap(path).points, finite(pcl), what);
  };
  pcl::io::savePCDFileASCII(path, xyz);
  check("xyz ascii");
  pcl::io::savePCDFileBinary(path, xyz);
  check("xyz binary");
  pcl::io::savePCDFileBinaryCompressed(path, xyz);
  check("xyz binary_compressed");
  pcl::io::savePCDFileASCII(path, rich);
  check("xyzrgbnormal ascii");
  pcl::io::savePCDFileBinary(path, rich);
  check("xyzrgbnormal binary");
  pcl::io::savePCDFileBinaryCompressed(path, rich);
  check("xyzrgbnormal binary_compressed");
}

// PCL converts the first ASCII value through a stream and the rest with atof (pcd_reader.cpp,
// PclAsciiNumbers); files whose first values take that path differently give PCL's points, and so
// does a header without VERSION and COUNT (as PCD 0.6 wrote them).
TEST(PcdAndPcl, AsciiValuesAreConvertedAsPclConvertsThem) {
  TempDir dir;
  const std::string halfway = "1.00000005960464477550";  // strtof and atof-then-float differ
  const std::string xyz = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
                          "POINTS 2\nDATA ascii\n";
  const std::string files[] = {
      xyz + halfway + " " + halfway + " " + halfway + "\n" + halfway + " 1 1\n",
      "VERSION 0.7\nFIELDS i x y z\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
      "DATA ascii\nnan " + halfway + " " + halfway + " 1\n",           // "nan" leaves the stream alone
      xyz + "0x1p3 0x1p3 " + halfway + "\n0x1p3 2 3\n",               // the stream reads "0" and goes on
      "VERSION 0.7\nFIELDS i x y z\nSIZE 4 4 4 4\nTYPE I F F F\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
      "DATA ascii\n1.5 " + halfway + " " + halfway + " 1\n",           // an integer stops at '.'
      "VERSION 0.7\nFIELDS c x y z\nSIZE 1 4 4 4\nTYPE U F F F\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
      "DATA ascii\nnan " + halfway + " " + halfway + " 1\n",           // SIZE 1 streams "nan" too
      "VERSION 0.7\nFIELDS _ x y z\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
      "DATA ascii\n7 " + halfway + " " + halfway + " 1\n",             // padding is not converted
      xyz + "1e39 -1e39 1e-46\n1e-46 5 -0\n",                        // out of float's range: infinite
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA ascii\n1 2 3\n4 5 6\n",  // 0.6: no COUNT
  };
  for (std::size_t i = 0; i < std::size(files); ++i) {
    const std::string path = dir.write("quirk" + std::to_string(i) + ".pcd", files[i]);
    expectSamePoints(loadMap(path).points, finite(pclPoints(path)), "file " + std::to_string(i));
  }
}

// Every PCD file of the repository (the fuzz seeds): what we read is what PCL reads (for x, y, z of
// SIZE 8, what PCL decoded of them), or we refuse it, as before.
TEST(PcdAndPcl, TheRepositorysPcdFilesGivePclsPoints) {
  const char* root = std::getenv("UAMPC_SOURCE_DIR");
  ASSERT_NE(root, nullptr);
  std::size_t compared = 0, refused = 0;
  for (auto it = std::filesystem::recursive_directory_iterator(root); it != std::filesystem::end(it); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_directory() && (name.rfind("build", 0) == 0 || name == ".git")) {
      it.disable_recursion_pending();
      continue;
    }
    if (it->path().extension() != ".pcd") continue;
    const std::string path = it->path().string();
    std::vector<Eigen::Vector3f> ours;
    try {
      ours = loadMap(path).points;
    } catch (const std::runtime_error& e) {
      ++refused;
      EXPECT_NE(name.find("regression"), std::string::npos) << "refused: " << e.what();
      continue;
    }
    const std::vector<Eigen::Vector3f> pcl = coordinatesAreDoubles(path) ? pclDoublePoints(path) : pclPoints(path);
    expectSamePoints(ours, finite(pcl), path);
    ++compared;
    std::cout << path << ": " << ours.size() << " points, the same as PCL's\n";
  }
  EXPECT_GE(compared, 5u);
  EXPECT_EQ(refused, 2u);
}

}  // namespace
}  // namespace uampc::world
