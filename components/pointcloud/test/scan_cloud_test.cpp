#include <gtest/gtest.h>

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
  auto bad_time = makeScanCloud(threePoints(), "lidar");
  bad_time.fields()[4].datatype(2);  // t as uint8
  EXPECT_THROW(findTimeField(bad_time), std::runtime_error);
}

}  // namespace
}  // namespace uampc::pointcloud
