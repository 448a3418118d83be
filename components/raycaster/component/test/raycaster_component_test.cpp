// The adapter in-process: nothing is rendered until the world, the poses and the encoder states
// cover a frame; then frame k covers [k/rate, (k+1)/rate) with every point at its own time.
#include <gtest/gtest.h>

#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

// The inside of a box, 20 m x 20 m x 10 m around the origin: 8 corners, 12 triangles, one chunk.
msg::WorldMesh boxWorld() {
  msg::WorldMesh m;
  m.world("box");
  m.chunk(0);
  m.chunk_count(1);
  for (int i = 0; i < 8; ++i) {
    m.vertices().push_back(i & 1 ? 10.0f : -10.0f);
    m.vertices().push_back(i & 2 ? 10.0f : -10.0f);
    m.vertices().push_back(i & 4 ? 5.0f : -5.0f);
  }
  const std::uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    for (std::uint32_t v : {f[0], f[1], f[2], f[0], f[2], f[3]}) m.triangles().push_back(v);
  }
  return m;
}

void injectPosesAndEncoder(testing::TestContext& ctx, int from_step, int to_step) {
  for (int k = from_step; k <= to_step; ++k) {
    const Time t = Time::fromSeconds(0.005 * k);
    geometry_msgs::msg::PoseStamped pose;
    pose.header().stamp(toMsg(t));
    pose.pose().orientation().w(1.0);
    ctx.inject("ground_truth", pose);
    sensor_msgs::msg::JointState state;
    state.header().stamp(toMsg(t));
    state.position({3.6 * t.seconds()});
    state.velocity({3.6});
    ctx.inject("motor_state", state);
  }
}

TEST(RaycasterComponent, RendersEachFrameOnceItsPosesAndEncoderStatesArrive) {
  testing::TestContext ctx("raycaster", {{"range_noise", "0"}});
  ctx.inject("world", boxWorld());
  injectPosesAndEncoder(ctx, 0, 15);  // to 0.075 s: frame 0 ([0, 0.1) s) not covered
  EXPECT_EQ(ctx.publishedCount("scan"), 0u);
  injectPosesAndEncoder(ctx, 16, 30);  // to 0.15 s
  ASSERT_EQ(ctx.publishedCount("scan"), 1u);
  injectPosesAndEncoder(ctx, 31, 40);  // to 0.2 s
  const auto scans = ctx.published<sensor_msgs::msg::PointCloud2>("scan");
  ASSERT_EQ(scans.size(), 2u);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    EXPECT_EQ(fromMsg(scans[k].header().stamp()), Time::fromSeconds(0.1 * static_cast<double>(k)));
    const pointcloud::TimeField time_field = pointcloud::findTimeField(scans[k]);
    const pointcloud::ScanPoints points = pointcloud::readCloud(scans[k], &time_field);
    ASSERT_GT(points.positions.size(), 1000u);
    for (std::size_t i = 0; i < points.positions.size(); ++i) {
      ASSERT_GE(points.time_offsets[i], 0.0f);
      ASSERT_LT(points.time_offsets[i], 0.1f);
      // No return from beyond the box's far corner (LiDAR at the origin, 0.5 m of rig at most).
      ASSERT_LT(points.positions[i].norm(), 16.0f);
    }
  }
}

TEST(RaycasterComponent, RefusesAWorldChunkThatNamesAVertexItDoesNotHave) {
  testing::TestContext ctx("raycaster");
  msg::WorldMesh bad = boxWorld();
  bad.triangles()[4] = 8;
  EXPECT_THROW(ctx.inject("world", bad), std::runtime_error);
}

// A spinning LiDAR whose frame would not fit in memory is refused at start, naming the budget
// (1e8 points/s at 1 Hz, each within its bounds, needed more than 8 GB for one frame).
TEST(RaycasterComponent, RefusesAFrameBeyondThePointBudget) {
  try {
    testing::TestContext ctx(
        "raycaster", {{"lidar_model", "spinning"}, {"lidar_points_per_second", "1e8"}, {"lidar_frame_rate", "1"}});
    ADD_FAILURE() << "a 1e8-point frame was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("points per frame; at most 2000000 are simulated"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(testing::TestContext(
      "raycaster", {{"lidar_model", "spinning"}, {"lidar_points_per_second", "1e6"}, {"lidar_frame_rate", "1"}}));
}

}  // namespace
}  // namespace uampc
