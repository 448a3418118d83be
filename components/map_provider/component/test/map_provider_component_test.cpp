// The adapter in-process: the world goes out whole at construction (latched chunks, each naming
// its place), and the ground-truth pose follows the trajectory at the pose rate.
#include <gtest/gtest.h>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

TEST(MapProviderComponent, PublishesTheWorldInNumberedChunksAndPosesAtThePoseRate) {
  testing::TestContext ctx(
      "map_provider", {{"world", "corridor"}, {"pose_rate", "50"}, {"path_speed", "2"}, {"chunk_triangles", "100"}});
  const auto chunks = ctx.published<msg::WorldMesh>("world");
  ASSERT_FALSE(chunks.empty());
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    EXPECT_EQ(chunks[i].chunk(), i);
    EXPECT_EQ(chunks[i].chunk_count(), chunks.size());
    EXPECT_LE(chunks[i].triangles().size(), 3u * 100u);
  }
  EXPECT_EQ(ctx.publishedCount("map"), 1u);
  EXPECT_EQ(ctx.publishedCount("ground_truth"), 0u);  // poses come with the clock

  ctx.advanceTo(Time::fromSeconds(1.0));
  const auto poses = ctx.published<geometry_msgs::msg::PoseStamped>("ground_truth");
  ASSERT_EQ(poses.size(), 51u);
  EXPECT_EQ(fromMsg(poses[50].header().stamp()), Time::fromSeconds(1.0));
  // A generated path at 2 m/s: 0.04 m between samples 20 ms apart.
  const Eigen::Vector3d step =
      adapters::toIsometry(poses[26].pose()).translation() - adapters::toIsometry(poses[25].pose()).translation();
  EXPECT_NEAR(step.norm(), 0.04, 1e-3);
}

}  // namespace
}  // namespace uampc
