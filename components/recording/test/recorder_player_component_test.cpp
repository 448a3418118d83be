// The recorder and player components through the in-process test context: the recorder asks for
// the scene's topics and writes what arrives with its times; the player publishes a recording at
// its recorded steps.
#include <gtest/gtest.h>

#include <filesystem>

#include "uampc/recording/playback.hpp"
#include "uampc/recording/recording_writer.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

namespace fs = std::filesystem;
using testing::TestContext;
using testing::TestOptions;

std::string tempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "uampc_recorder_player_test";
  fs::create_directories(dir);
  return (dir / name).string();
}

SerializedMessage bytes(std::uint8_t tag) { return {{0, 1, 0, 0, tag, tag, tag, tag}}; }

PortSpec output(const std::string& topic, const std::string& type, QosPreset qos) {
  return {"out", PortDirection::kOutput, type, topic, qos, "a writer of the scene"};
}

TEST(RecorderComponent, RecordsEveryWrittenTopicWithArrivalAndPublishTimes) {
  const std::string file = tempFile("recorded.mcap");
  TestOptions options;
  options.scene_outputs = {output("/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl),
                           output("/lidar/points", "sensor_msgs/msg/PointCloud2", QosPreset::kSensor)};
  {
    TestContext ctx("recorder", {{"file", file}}, options);
    ASSERT_EQ(ctx.ports().size(), 2u);
    EXPECT_EQ(ctx.ports()[0].direction, PortDirection::kInput);
    ctx.advanceTo(Time::fromSeconds(0.010));
    ctx.injectSerialized("/motor/state", bytes(1), Time::fromSeconds(0.005));
    ctx.injectSerialized("/lidar/points", bytes(2), Time::fromSeconds(0.005));
    ctx.advanceTo(Time::fromSeconds(0.015));
    ctx.injectSerialized("/motor/state", bytes(3), Time::fromSeconds(0.010));
    ctx.shutdown();
  }
  mcap::Reader reader(file);
  std::vector<std::tuple<std::string, std::uint64_t, std::uint64_t, std::uint8_t>> seen;
  reader.forEachMessage({}, 0, [&](const mcap::MessageView& m) {
    seen.emplace_back(m.channel->topic, m.log_time, m.publish_time, m.data[4]);
    return true;
  });
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0], std::make_tuple(std::string("/motor/state"), 10000000ull, 5000000ull, std::uint8_t{1}));
  EXPECT_EQ(seen[1], std::make_tuple(std::string("/lidar/points"), 10000000ull, 5000000ull, std::uint8_t{2}));
  EXPECT_EQ(seen[2], std::make_tuple(std::string("/motor/state"), 15000000ull, 10000000ull, std::uint8_t{3}));
  const recording::Playback playback(file, {});
  EXPECT_EQ(playback.clock(), recording::RecordingClock::kLockstep);
  ASSERT_EQ(playback.topics().size(), 2u);
  for (const auto& topic : playback.topics()) {
    EXPECT_EQ(topic.qos, topic.topic == "/lidar/points" ? QosPreset::kSensor : QosPreset::kControl) << topic.topic;
  }
}

TEST(RecorderComponent, ATopicNoComponentWritesIsRefusedWithAHint) {
  TestOptions options;
  options.scene_outputs = {output("/lidar/points", "sensor_msgs/msg/PointCloud2", QosPreset::kSensor)};
  try {
    TestContext ctx("recorder", {{"file", tempFile("never.mcap")}, {"topics", "[/lidar/pointz]"}}, options);
    FAIL() << "a topic nobody writes was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean /lidar/points?"), std::string::npos) << e.what();
  }
}

TEST(PlayerComponent, PublishesEachSampleInTheStepItWasRecorded) {
  const std::string file = tempFile("to_play.mcap");
  {
    recording::RecordingWriter writer(file, {mcap::Compression::kZstd, 1024, recording::RecordingClock::kLockstep});
    const auto state = writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
    const auto tf = writer.addTopic({"/tf_static", "tf2_msgs/msg/TFMessage", QosPreset::kLatched});
    writer.write(tf, Time::fromSeconds(0.005), Time{0}, bytes(9));
    for (int i = 1; i <= 4; ++i) {
      writer.write(state, Time::fromSeconds(0.005 * (i + 1)), Time::fromSeconds(0.005 * i), bytes(i));
    }
  }
  TestContext ctx("player", {{"file", file}});
  ASSERT_EQ(ctx.ports().size(), 2u);
  EXPECT_EQ(ctx.ports()[1].qos, QosPreset::kLatched);
  EXPECT_EQ(ctx.ports()[0].type_name, "sensor_msgs/msg/JointState");
  ctx.advanceTo(Time{0});
  EXPECT_EQ(ctx.publishedSerialized("/tf_static").size(), 1u);
  EXPECT_TRUE(ctx.publishedSerialized("/motor/state").empty());
  ctx.advanceTo(Time::fromSeconds(0.010));  // steps 0.005 and 0.010
  auto states = ctx.publishedSerialized("/motor/state");
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].data, bytes(1).data);
  EXPECT_EQ(states[1].data, bytes(2).data);
  ctx.advanceTo(Time::fromSeconds(1.0));
  EXPECT_EQ(ctx.publishedSerialized("/motor/state").size(), 4u);
}

TEST(PlayerComponent, StartSkipsTheFirstSecondsAndTopicsFilter) {
  const std::string file = tempFile("to_skip.mcap");
  {
    recording::RecordingWriter writer(file, {mcap::Compression::kNone, 1024, recording::RecordingClock::kLockstep});
    const auto state = writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
    const auto other = writer.addTopic({"/other", "sensor_msgs/msg/JointState", QosPreset::kControl});
    for (int i = 0; i < 10; ++i) {
      writer.write(state, Time::fromSeconds(0.1 * i + 0.005), Time::fromSeconds(0.1 * i), bytes(i));
      writer.write(other, Time::fromSeconds(0.1 * i + 0.005), Time::fromSeconds(0.1 * i), bytes(i));
    }
  }
  TestContext ctx("player", {{"file", file}, {"start", "0.5"}, {"topics", "[/motor/state]"}});
  ASSERT_EQ(ctx.ports().size(), 1u);
  ctx.advanceTo(Time{0});
  auto states = ctx.publishedSerialized("/motor/state");
  ASSERT_EQ(states.size(), 1u);  // recorded at 0.5 s, due at clock 0
  EXPECT_EQ(states[0].data, bytes(5).data);
  ctx.advanceTo(Time::fromSeconds(0.4));
  EXPECT_EQ(ctx.publishedSerialized("/motor/state").size(), 5u);
}

}  // namespace
}  // namespace uampc
