// sensor_msgs/PointCloud2 as the LO and the evaluator read them: any field layout (names,
// offsets, datatypes, counts, point_step, row_step, width x height, endianness) and any contents,
// delivered on their ports through the in-process test context (the components' own plugin
// libraries, as a scene loads them). The LO finds the time field, reads the cloud and, with an
// encoder state after the scan, registers it (twice: the second against the map of the first);
// the evaluator reads it as a raw scan (placed once ground truth and encoder cover it) and as a
// registered one (CMPLT). The MPC reads its local map with the same readCloud() as the
// evaluator's registered port.
//
// A component may throw on a cloud it cannot read: the runtime turns that into a failure naming
// the component and topic, a correct answer. Crashes, hangs, leaks and sanitizer reports are
// findings.
//
// Input (little-endian): u32 height, width, point_step, row_step; u8 is_bigendian, is_dense;
// i32 stamp sec, u32 nanosec; u8 field count, each field u8 name length, name, u32 offset,
// u8 datatype, u32 count; the rest is data. tests/fuzz/make_corpus.py writes seeds.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>

#include "byte_reader.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace {

using namespace uampc;

sensor_msgs::msg::PointCloud2 cloudFrom(fuzz::ByteReader& in) {
  sensor_msgs::msg::PointCloud2 cloud;
  cloud.height(in.u32());
  cloud.width(in.u32());
  cloud.point_step(in.u32());
  cloud.row_step(in.u32());
  cloud.is_bigendian(in.u8() != 0);
  cloud.is_dense(in.u8() != 0);
  cloud.header().stamp().sec(in.i32());
  cloud.header().stamp().nanosec(in.u32());
  cloud.header().frame_id("lidar");
  const int fields = in.u8();
  for (int i = 0; i < fields; ++i) {
    sensor_msgs::msg::PointField f;
    f.name(in.shortString());
    f.offset(in.u32());
    f.datatype(in.u8());
    f.count(in.u32());
    cloud.fields().push_back(f);
  }
  cloud.data(in.rest());
  return cloud;
}

sensor_msgs::msg::JointState encoderAt(double t) {
  sensor_msgs::msg::JointState s;
  s.header().stamp(toMsg(Time::fromSeconds(t)));
  s.position({0.5 * t});
  s.velocity({0.5});
  return s;
}

geometry_msgs::msg::PoseStamped truthAt(double t) {
  geometry_msgs::msg::PoseStamped p;
  p.header().stamp(toMsg(Time::fromSeconds(t)));
  p.pose().orientation().w(1.0);
  return p;
}

// Each delivery as the runtime makes it: an exception is the component's named failure.
void deliver(const std::function<void()>& delivery) {
  try {
    delivery();
  } catch (const std::exception&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const sensor_msgs::msg::PointCloud2 cloud = cloudFrom(in);
  const double stamp = fromMsg(cloud.header().stamp()).seconds();
  // Encoder and ground truth from before the scan to after any point time readCloud keeps.
  const double before = stamp - 1.0, after = stamp + 2.0 * pointcloud::kMaxTimeOffset;
  {
    testing::TestContext lo("lo", {{"init_from_pose", "false"}, {"max_motor_wait", "0"}});
    deliver([&] { lo.inject("motor_state", encoderAt(before)); });
    deliver([&] { lo.inject("scan", cloud); });
    deliver([&] { lo.inject("motor_state", encoderAt(after)); });
    deliver([&] { lo.inject("scan", cloud); });
    deliver([&] { lo.inject("motor_state", encoderAt(after + 1.0)); });
  }
  {
    testing::TestContext evaluator("evaluator");
    deliver([&] { evaluator.inject("motor_state", encoderAt(before)); });
    deliver([&] { evaluator.inject("ground_truth", truthAt(before)); });
    deliver([&] { evaluator.inject("scan", cloud); });
    deliver([&] { evaluator.inject("registered", cloud); });
    deliver([&] { evaluator.inject("motor_state", encoderAt(after)); });
    deliver([&] { evaluator.inject("ground_truth", truthAt(after)); });
  }
  return 0;
}
