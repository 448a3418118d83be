// Test component: publishes a known PointCloud2 and Odometry (see tests/wire/wire_sample.hpp)
// every 50 ms, for the test that another DDS vendor decodes our wire format.
#include <cstring>

#include "../wire/wire_sample.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class WirePublisher : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: publishes known PointCloud2 and Odometry samples";
    spec.output<sensor_msgs::msg::PointCloud2>("points", "/wire_test/points", QosPreset::kControl, "known cloud");
    spec.output<nav_msgs::msg::Odometry>("odometry", "/wire_test/odometry", QosPreset::kControl, "known odometry");
  }

  explicit WirePublisher(Context& ctx)
      : points_(ctx.publisher<sensor_msgs::msg::PointCloud2>("points")),
        odometry_(ctx.publisher<nav_msgs::msg::Odometry>("odometry")) {
    ctx.timer(0.05, [this] { publish(); });
  }

 private:
  // Built here from wire_sample.hpp's values, not with uampc_pointcloud: the sample's every byte
  // must be known to the other vendor's subscriber, whatever that library's layout becomes.
  static sensor_msgs::msg::PointField field(const char* name, std::uint32_t offset, std::uint8_t type) {
    sensor_msgs::msg::PointField f;
    f.name(name);
    f.offset(offset);
    f.datatype(type);
    f.count(1);
    return f;
  }

  void publish() {
    sensor_msgs::msg::PointCloud2 cloud;
    cloud.header().stamp().sec(1644823132);
    cloud.header().stamp().nanosec(492110014);
    cloud.header().frame_id("lidar");
    cloud.height(1);
    cloud.width(WIRE_POINT_COUNT);
    cloud.fields({field("x", 0, 7), field("y", 4, 7), field("z", 8, 7), field("intensity", 12, 7),
                  field("t", 16, 7), field("ring", 20, 4)});
    cloud.is_bigendian(false);
    cloud.point_step(WIRE_POINT_STEP);
    cloud.row_step(WIRE_POINT_STEP * WIRE_POINT_COUNT);
    std::vector<std::uint8_t> data(WIRE_POINT_STEP * WIRE_POINT_COUNT);
    for (int i = 0; i < WIRE_POINT_COUNT; ++i) {
      const float values[] = {wireX(i), wireY(i), wireZ(i), wireIntensity(i), wireTime(i)};
      const unsigned short ring = wireRing(i);
      std::memcpy(&data[i * WIRE_POINT_STEP], values, sizeof values);
      std::memcpy(&data[i * WIRE_POINT_STEP + 20], &ring, sizeof ring);
    }
    cloud.data(data);
    cloud.is_dense(true);
    points_.publish(cloud);

    nav_msgs::msg::Odometry odom;
    odom.header().stamp().sec(42);
    odom.header().stamp().nanosec(5);
    odom.header().frame_id("map");
    odom.child_frame_id("base");
    odom.pose().pose().position().x(1.5);
    odom.pose().pose().position().y(-2.25);
    odom.pose().pose().position().z(3.125);
    odom.pose().pose().orientation().x(0.0);
    odom.pose().pose().orientation().y(0.0);
    odom.pose().pose().orientation().z(0.6);
    odom.pose().pose().orientation().w(0.8);
    for (int i = 0; i < 36; ++i) {
      odom.pose().covariance()[i] = wireCovariance(i);
      odom.twist().covariance()[i] = -wireCovariance(i);
    }
    odom.twist().twist().linear().x(0.5);
    odom.twist().twist().angular().z(3.6);
    odometry_.publish(odom);
  }

  Publisher<sensor_msgs::msg::PointCloud2> points_;
  Publisher<nav_msgs::msg::Odometry> odometry_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::WirePublisher, "wire_publisher")
