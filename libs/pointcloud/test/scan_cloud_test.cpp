#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "uampc/pointcloud/scan_cloud.hpp"

namespace uampc::pointcloud {
namespace {

ScanPoints threePoints() {
  ScanPoints p;
  p.positions = {{1, 2, 3}, {-4, 5.5f, 0}, {0.25f, 0, -7}};
  p.intensities = {10, 20, 30};
  p.time_offsets = {0.0f, 0.05f, 0.099f};
  p.rings = {0, 3, 7};
  return p;
}

TEST(ScanCloud, RoundTripsEveryField) {
  const auto cloud = makeScanCloud(threePoints(), "lidar");
  EXPECT_EQ(cloud.point_step(), 22u);
  EXPECT_EQ(cloud.data().size(), 66u);
  const TimeField tf = findTimeField(cloud);
  EXPECT_EQ(tf.name, "t");
  const ScanPoints back = readCloud(cloud, &tf);
  const ScanPoints want = threePoints();
  ASSERT_EQ(back.positions.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(back.positions[i], want.positions[i]);
    EXPECT_EQ(back.intensities[i], want.intensities[i]);
    EXPECT_EQ(back.time_offsets[i], want.time_offsets[i]);
    EXPECT_EQ(back.rings[i], want.rings[i]);
  }
}

// livox_ros_driver2's PointCloud2 (xfer_format 0): 26 bytes a point, timestamp float64 in absolute
// nanoseconds on the header's clock (a PTP-synchronised Mid-360 in 2026: 1.79e18 ns).
TEST(ScanCloud, ReadsLivoxDriverCloudsWithAbsoluteNanosecondTimes) {
  const std::int64_t stamp_ns = 1'795'464'880'913'398'000;
  const auto cloud = makeLivoxCloud(threePoints(), "livox_frame", stamp_ns);
  EXPECT_EQ(cloud.point_step(), 26u);
  ASSERT_EQ(cloud.fields().size(), 7u);
  EXPECT_EQ(cloud.fields()[6].name(), "timestamp");
  EXPECT_EQ(cloud.fields()[6].offset(), 18u);
  double first = 0;
  std::memcpy(&first, cloud.data().data() + 18, 8);
  EXPECT_EQ(first, static_cast<double>(stamp_ns));  // absolute, not an offset
  const TimeField tf = findTimeField(cloud);
  EXPECT_TRUE(tf.absolute);
  const ScanPoints back = readCloud(cloud, &tf);
  const ScanPoints want = threePoints();
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(back.positions[i], want.positions[i]);
    EXPECT_NEAR(back.time_offsets[i], want.time_offsets[i], 1e-6);  // double ns: 256 ns steps at 1.8e18
  }
  EXPECT_TRUE(back.rings.empty());  // the layout has line, not ring
}

// Hesai's and RoboSense's drivers write the same field in absolute seconds.
TEST(ScanCloud, ReadsAbsoluteSecondTimestampsToo) {
  auto cloud = makeLivoxCloud(threePoints(), "lidar", 0);
  builtin_interfaces::msg::Time stamp;
  stamp.sec(1'795'464'880);
  stamp.nanosec(500'000'000);
  cloud.header().stamp(stamp);
  const double seconds[3] = {1'795'464'880.5, 1'795'464'880.55, 1'795'464'880.599};
  for (int i = 0; i < 3; ++i) std::memcpy(cloud.data().data() + 26 * i + 18, &seconds[i], 8);
  const TimeField tf = findTimeField(cloud);
  const ScanPoints back = readCloud(cloud, &tf);
  EXPECT_NEAR(back.time_offsets[0], 0.0, 1e-6);
  EXPECT_NEAR(back.time_offsets[1], 0.05, 1e-6);
  EXPECT_NEAR(back.time_offsets[2], 0.099, 1e-6);
}

// Another driver's layout: x y z, then offset_time as uint32 nanoseconds (as Livox's driver).
TEST(ScanCloud, ReadsOtherDriversTimeFieldsInNanoseconds) {
  auto cloud = makeXyzCloud({{1, 1, 1}, {2, 2, 2}}, "lidar");
  sensor_msgs::msg::PointField f;
  f.name("offset_time");
  f.offset(12);
  f.datatype(6);
  f.count(1);
  cloud.fields().push_back(f);
  cloud.point_step(16);
  std::vector<std::uint8_t> data(32);
  for (int i = 0; i < 2; ++i) {
    const float xyz[3] = {float(i + 1), float(i + 1), float(i + 1)};
    const std::uint32_t ns = 50000000u * static_cast<std::uint32_t>(i);
    std::memcpy(&data[16 * i], xyz, 12);
    std::memcpy(&data[16 * i + 12], &ns, 4);
  }
  cloud.data(data);
  const TimeField tf = findTimeField(cloud);
  EXPECT_EQ(tf.name, "offset_time");
  const ScanPoints back = readCloud(cloud, &tf);
  EXPECT_FLOAT_EQ(back.time_offsets[1], 0.05f);
  EXPECT_TRUE(back.intensities.empty());
}

// Found by tests/fuzz/pointcloud2: a point 1000 s after the stamp made the evaluator build four
// million poses for the scan (a point at 1e30 s held it, and every scan after it, back for good);
// a float64 time beyond float's range was converted to float, which is undefined.
TEST(ScanCloud, PointTimesFartherThanAFrameCouldLastAreNotANumber) {
  const std::vector<double> times = {0.05, 1e300, -20.0, 1000.0, -kMaxTimeOffset, 9.5};
  auto cloud = makeXyzCloud(std::vector<Eigen::Vector3f>(times.size(), Eigen::Vector3f(1, 2, 3)), "lidar");
  sensor_msgs::msg::PointField f;
  f.name("timestamp");
  f.offset(12);
  f.datatype(8);  // float64
  f.count(1);
  cloud.fields().push_back(f);
  cloud.point_step(20);
  cloud.row_step(20 * static_cast<std::uint32_t>(times.size()));
  std::vector<std::uint8_t> data(20 * times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    const float xyz[3] = {1, 2, 3};
    std::memcpy(&data[20 * i], xyz, 12);
    std::memcpy(&data[20 * i + 12], &times[i], 8);
  }
  cloud.data(data);
  const TimeField tf = findTimeField(cloud);
  const ScanPoints back = readCloud(cloud, &tf);
  ASSERT_EQ(back.time_offsets.size(), times.size());
  EXPECT_FLOAT_EQ(back.time_offsets[0], 0.05f);
  EXPECT_TRUE(std::isnan(back.time_offsets[1]));
  EXPECT_TRUE(std::isnan(back.time_offsets[2]));
  EXPECT_TRUE(std::isnan(back.time_offsets[3]));
  EXPECT_FLOAT_EQ(back.time_offsets[4], -static_cast<float>(kMaxTimeOffset));
  EXPECT_FLOAT_EQ(back.time_offsets[5], 9.5f);
  EXPECT_EQ(back.positions.size(), times.size());  // the points stay; only their time is unknown
}

// Packed x, y, z clouds (the LO's local map) are read in one copy; the same points with another
// layout go point by point; both must give the points back, bit for bit.
TEST(ScanCloud, ReadsXyzCloudsOfEveryLayout) {
  const std::vector<Eigen::Vector3f> points = {{1, 2, 3}, {-4, 5.5f, -0.0f}, {1e-30f, 3e38f, -7}};
  const ScanPoints packed = readCloud(makeXyzCloud(points, "odom"));
  ASSERT_EQ(packed.positions.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(std::memcmp(packed.positions[i].data(), points[i].data(), 12), 0) << "point " << i;
  }
  EXPECT_TRUE(packed.intensities.empty());
  EXPECT_TRUE(readCloud(makeXyzCloud({}, "odom")).positions.empty());

  // The same 12 bytes a point, with the coordinates stored in the order z, x, y.
  auto shuffled = makeXyzCloud(points, "odom");
  shuffled.fields()[0].offset(4);  // x
  shuffled.fields()[1].offset(8);  // y
  shuffled.fields()[2].offset(0);  // z
  const ScanPoints from_shuffled = readCloud(shuffled);
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Stored bytes (x, y, z) are read as x = bytes 4-7 (y), y = bytes 8-11 (z), z = bytes 0-3 (x).
    EXPECT_EQ(from_shuffled.positions[i], Eigen::Vector3f(points[i].y(), points[i].z(), points[i].x()));
  }

  // 16 bytes a point (padding after z): read point by point, the same points.
  auto padded = makeXyzCloud(points, "odom");
  padded.point_step(16);
  padded.row_step(16 * static_cast<std::uint32_t>(points.size()));
  padded.data().assign(16 * points.size(), 0xAB);
  for (std::size_t i = 0; i < points.size(); ++i) std::memcpy(&padded.data()[16 * i], points[i].data(), 12);
  const ScanPoints from_padded = readCloud(padded);
  ASSERT_EQ(from_padded.positions.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(from_padded.positions[i], points[i]) << "point " << i;
}

TEST(ScanCloud, RefusesCloudsItCannotRead) {
  auto cloud = makeXyzCloud({{1, 1, 1}}, "map");
  EXPECT_THROW(findTimeField(cloud), std::runtime_error);  // no time field: says which fields exist
  try {
    findTimeField(cloud);
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the cloud has: x, y, z"), std::string::npos) << e.what();
  }
  cloud.width(5);  // claims more points than data holds
  EXPECT_THROW(readCloud(cloud), std::runtime_error);
  // A header whose width x height x point_step is 2^64, 0 in 64 bits: still "more than data holds",
  // not an attempt to allocate 2^60 points.
  cloud.width(1u << 30);
  cloud.height(1u << 30);
  cloud.point_step(16);
  try {
    readCloud(cloud);
    ADD_FAILURE() << "a cloud of 2^60 points in 12 bytes was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fewer than its 1152921504606846976 points"), std::string::npos) << e.what();
  }
  auto bad_time = makeScanCloud(threePoints(), "lidar");
  bad_time.fields()[4].datatype(2);  // t as uint8
  EXPECT_THROW(findTimeField(bad_time), std::runtime_error);
}

}  // namespace
}  // namespace uampc::pointcloud
