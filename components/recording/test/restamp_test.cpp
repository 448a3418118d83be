// `uampc play --restamp`: header stamps and a Livox cloud's absolute point times move together, so
// that the played scan reads the same (its points' offsets from the stamp) at its new time.
#include <gtest/gtest.h>

#include <cstring>

#include "uampc/msgs/rosgraph_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/recording/restamp.hpp"
#include "uampc/runtime/typed_sample.hpp"

namespace uampc::recording {
namespace {

template <typename Message>
SerializedMessage serialize(Message message) {
  return encodeSample(message);
}

template <typename Message>
Message deserialize(const SerializedMessage& sample) {
  Message message;
  EXPECT_TRUE(decodeSample(sample, message));
  return message;
}

const Time kOffset = Time::fromSeconds(1'795'464'000.25);  // a lockstep recording's 12 s, moved to 2026

TEST(Restamp, MovesAHeaderStamp) {
  sensor_msgs::msg::JointState state;
  state.header().stamp(toMsg(Time::fromSeconds(12.5)));
  state.header().frame_id("motor");
  state.position({1.5});
  SerializedMessage sample = serialize(state);
  Restamper restamper(kOffset);
  EXPECT_TRUE(restamper.restamp("/motor/state", "sensor_msgs/msg/JointState", sample));
  const auto moved = deserialize<sensor_msgs::msg::JointState>(sample);
  EXPECT_EQ(fromMsg(moved.header().stamp()).ns, (Time::fromSeconds(12.5) + kOffset).ns);
  EXPECT_EQ(moved.header().frame_id(), "motor");
  EXPECT_EQ(moved.position(), std::vector<double>{1.5});
}

TEST(Restamp, MovesALivoxCloudsPointTimesWithItsStamp) {
  pointcloud::ScanPoints points;
  points.positions = {{1, 2, 3}, {4, 5, 6}};
  points.time_offsets = {0.0f, 0.099f};
  const Time stamp = Time::fromSeconds(12.0);
  SerializedMessage sample = serialize(pointcloud::makeLivoxCloud(points, "livox_frame", stamp.ns));
  Restamper restamper(kOffset);
  EXPECT_TRUE(restamper.restamp("/livox/lidar", "sensor_msgs/msg/PointCloud2", sample));
  const auto moved = deserialize<sensor_msgs::msg::PointCloud2>(sample);
  EXPECT_EQ(fromMsg(moved.header().stamp()).ns, (stamp + kOffset).ns);
  double first = 0;
  std::memcpy(&first, moved.data().data() + 18, 8);
  EXPECT_NEAR(first, static_cast<double>((stamp + kOffset).ns), 512.0);  // double ns at 1.8e18
  const pointcloud::TimeField field = pointcloud::findTimeField(moved);
  const pointcloud::ScanPoints read = pointcloud::readCloud(moved, &field);
  EXPECT_NEAR(read.time_offsets[0], 0.0, 1e-6);
  EXPECT_NEAR(read.time_offsets[1], 0.099, 1e-6);
}

TEST(Restamp, LeavesACloudWithRelativeTimesAsItWasButItsStamp) {
  pointcloud::ScanPoints points;
  points.positions = {{1, 2, 3}, {4, 5, 6}};
  points.time_offsets = {0.0f, 0.099f};
  auto cloud = pointcloud::makeScanCloud(points, "lidar");
  cloud.header().stamp(toMsg(Time::fromSeconds(12.0)));
  Restamper restamper(kOffset);
  for (int i = 0; i < 2; ++i) {  // the second from the per-topic cache
    SerializedMessage sample = serialize(cloud);
    EXPECT_TRUE(restamper.restamp("/lidar/points", "sensor_msgs/msg/PointCloud2", sample));
    const auto moved = deserialize<sensor_msgs::msg::PointCloud2>(sample);
    EXPECT_EQ(fromMsg(moved.header().stamp()).ns, (Time::fromSeconds(12.0) + kOffset).ns);
    EXPECT_EQ(moved.data(), cloud.data());
  }
}

TEST(Restamp, LeavesATypeWithoutHeaderAlone) {
  rosgraph_msgs::msg::Clock clock;
  clock.clock(toMsg(Time::fromSeconds(3.0)));
  SerializedMessage sample = serialize(clock);
  const SerializedMessage before = sample;
  Restamper restamper(kOffset);
  EXPECT_FALSE(restamper.restamp("/clock", "rosgraph_msgs/msg/Clock", sample));
  EXPECT_EQ(sample.data, before.data);
}

TEST(Restamp, RefusesASampleTooShortForItsHeader) {
  SerializedMessage sample{{0x00, 0x01, 0x00, 0x00, 0x01}};
  Restamper restamper(kOffset);
  EXPECT_THROW(restamper.restamp("/lidar/imu", "sensor_msgs/msg/Imu", sample), std::runtime_error);
}

}  // namespace
}  // namespace uampc::recording
