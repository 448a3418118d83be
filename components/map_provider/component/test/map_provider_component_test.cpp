// The adapter in-process: the world goes out whole at construction (latched chunks, each naming
// its place), and the ground-truth pose follows the trajectory at the pose rate.
#include <gtest/gtest.h>

#include <cmath>

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

// A world that would need more chunks than a latched topic keeps for late joiners goes out in
// larger ones, never more than kLatchedHistoryDepth, every point still in them.
TEST(MapProviderComponent, ALargeWorldFitsTheLatchedHistory) {
  auto points_in = [](const std::vector<msg::WorldMesh>& chunks) {
    std::size_t n = 0;
    for (const auto& c : chunks) n += c.points().size() / 3;
    return n;
  };
  testing::TestContext small_chunks(
      "map_provider", {{"world", "corridor"}, {"point_map_resolution", "0.2"}, {"chunk_triangles", "100"}});
  const auto chunks = small_chunks.published<msg::WorldMesh>("world");
  ASSERT_FALSE(chunks.empty());
  EXPECT_LE(chunks.size(), static_cast<std::size_t>(kLatchedHistoryDepth));
  EXPECT_EQ(chunks.front().chunk_count(), chunks.size());
  testing::TestContext one_chunk(
      "map_provider", {{"world", "corridor"}, {"point_map_resolution", "0.2"}, {"chunk_triangles", "1000000"}});
  const auto whole = one_chunk.published<msg::WorldMesh>("world");
  ASSERT_EQ(whole.size(), 1u);
  // 300 points a chunk would take more than the history's 100 chunks.
  ASSERT_GT(points_in(whole), 300u * static_cast<std::size_t>(kLatchedHistoryDepth));
  EXPECT_EQ(points_in(chunks), points_in(whole));
  EXPECT_NEAR(whole.front().point_radius(), 0.55 * std::sqrt(3.0) * 0.2, 1e-6);
}

}  // namespace
}  // namespace uampc
