// The recording core: what the writer puts in a file is what Playback gives back, with the right
// types, QoS, clock and due times, a window at a time; bad recordings are refused by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "uampc/mcap/mcap.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/recording/playback.hpp"
#include "uampc/recording/recording_writer.hpp"

namespace uampc::recording {
namespace {

namespace fs = std::filesystem;

std::string tempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "uampc_recording_test";
  fs::create_directories(dir);
  return (dir / name).string();
}

SerializedMessage bytes(std::uint8_t tag, std::size_t size = 16) {
  SerializedMessage m;
  m.data.assign(size, tag);
  m.data[0] = 0;  // CDR_LE encapsulation header
  m.data[1] = 1;
  return m;
}

TEST(Recording, TopicsTypesQosAndSamplesComeBack) {
  const std::string file = tempFile("round_trip.mcap");
  {
    RecordingWriter writer(file, {mcap::Compression::kZstd, 1024, RecordingClock::kRealtime});
    bool unknown = true;
    const auto scan = writer.addTopic({"/lidar/points", "sensor_msgs/msg/PointCloud2", QosPreset::kSensor}, &unknown);
    EXPECT_FALSE(unknown);
    const auto state = writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
    for (int i = 0; i < 50; ++i) {
      writer.write(state, Time::fromSeconds(0.1 * i + 0.01), Time::fromSeconds(0.1 * i), bytes(i, 200));
      if (i % 10 == 0)
        writer.write(scan, Time::fromSeconds(0.1 * i + 0.02), Time::fromSeconds(0.1 * i), bytes(100 + i, 5000));
    }
    writer.close();
    EXPECT_EQ(writer.messages(), 55u);
  }
  // The schema is the type's ros2msg definition, as rosbag2 writes it.
  mcap::Reader reader(file);
  ASSERT_EQ(reader.schemas().size(), 2u);
  for (const auto& schema : reader.schemas()) {
    EXPECT_EQ(schema.encoding, "ros2msg");
    EXPECT_EQ(schema.data, messageDefinition(schema.name));
    EXPECT_FALSE(schema.data.empty());
  }

  Playback playback(file, {});
  ASSERT_EQ(playback.topics().size(), 2u);
  EXPECT_EQ(playback.topics()[0].topic, "/lidar/points");
  EXPECT_EQ(playback.topics()[0].type, "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(playback.topics()[0].qos, QosPreset::kSensor);
  EXPECT_EQ(playback.topics()[1].qos, QosPreset::kControl);
  EXPECT_EQ(playback.clock(), RecordingClock::kRealtime);
  EXPECT_EQ(playback.sampleCount(), 55u);
  EXPECT_EQ(playback.start(), Time::fromSeconds(0.01));  // real time: due at the log time

  // Due at their log times, in order; nothing before it is due.
  RecordedSample s;
  EXPECT_FALSE(playback.next(Time::fromSeconds(0.005), s));
  std::vector<RecordedSample> all;
  for (double t = 0; t < 6.0; t += 0.05) {
    while (playback.next(Time::fromSeconds(t), s)) {
      EXPECT_LE(s.time, Time::fromSeconds(t));
      all.push_back(s);
    }
  }
  ASSERT_EQ(all.size(), 55u);
  EXPECT_TRUE(playback.finished());
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_LE(all[i - 1].time, all[i].time);
  EXPECT_EQ(all[0].data.data, bytes(0, 200).data);
  EXPECT_EQ(all[1].topic, 0u);
  EXPECT_EQ(all[1].data.data, bytes(100, 5000).data);

  playback.seek(playback.start());
  ASSERT_TRUE(playback.next(Time::fromSeconds(0.01), s));
  EXPECT_EQ(s.data.data, bytes(0, 200).data);
}

TEST(Recording, LockstepRecordingsAreDueWhenPublishedAndGapsAreCrossed) {
  const std::string file = tempFile("lockstep.mcap");
  {
    RecordingWriter writer(file, {mcap::Compression::kLz4, 4096, RecordingClock::kLockstep});
    const auto state = writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
    // A latched sample at 0, then a gap of 7 s (longer than the read-ahead window).
    writer.write(state, Time::fromSeconds(0.005), Time{0}, bytes(1));
    writer.write(state, Time::fromSeconds(7.005), Time::fromSeconds(7.0), bytes(2));
    writer.write(state, Time::fromSeconds(7.010), Time::fromSeconds(7.005), bytes(3));
  }
  Playback playback(file, {"/motor/state"});
  EXPECT_EQ(playback.clock(), RecordingClock::kLockstep);
  EXPECT_EQ(playback.start(), Time{0});
  RecordedSample s;
  ASSERT_TRUE(playback.next(Time{0}, s));
  EXPECT_EQ(s.time, Time{0});
  EXPECT_FALSE(playback.next(Time::fromSeconds(6.995), s));
  ASSERT_TRUE(playback.next(Time::fromSeconds(7.0), s));
  EXPECT_EQ(s.data.data, bytes(2).data);
  EXPECT_FALSE(playback.next(Time::fromSeconds(7.0), s));
  ASSERT_TRUE(playback.next(Time::fromSeconds(7.005), s));
  EXPECT_EQ(s.data.data, bytes(3).data);
  EXPECT_TRUE(playback.finished());
  // Seeking skips what was logged before, without reading it.
  playback.seek(Time::fromSeconds(7.0));
  ASSERT_TRUE(playback.next(Time::fromSeconds(7.005), s));
  EXPECT_EQ(s.data.data, bytes(2).data);
}

// A lockstep run's own topics are never played, asked for or not: a live run on the domain would take
// them for another run's (docs/decisions/replay-leaves-lockstep-topics.md).
TEST(Recording, ClockAndLockstepProtocolTopicsAreNeverPlayed) {
  const std::string file = tempFile("protocol_topics.mcap");
  {
    RecordingWriter writer(file, {});
    const auto clock = writer.addTopic({"/clock", "rosgraph_msgs/msg/Clock", QosPreset::kControl});
    const auto progress = writer.addTopic({"/uampc/lockstep/progress", "uampc/msg/StepAck", QosPreset::kControl});
    const auto state = writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
    writer.write(clock, Time{1}, Time{1}, bytes(1));
    writer.write(progress, Time{2}, Time{2}, bytes(2));
    writer.write(state, Time{3}, Time{3}, bytes(3));
  }
  for (const std::vector<std::string>& asked :
       {std::vector<std::string>{}, std::vector<std::string>{"/clock", "/uampc/lockstep/progress", "/motor/state"}}) {
    Playback playback(file, asked);
    ASSERT_EQ(playback.topics().size(), 1u);
    EXPECT_EQ(playback.topics()[0].topic, "/motor/state");
    EXPECT_EQ(playback.skipped(), (std::vector<std::string>{"/clock", "/uampc/lockstep/progress"}));
    RecordedSample s;
    ASSERT_TRUE(playback.next(Time{3}, s));
    EXPECT_EQ(s.data.data, bytes(3).data);
    EXPECT_FALSE(playback.next(Time{3}, s));
  }
}

TEST(Recording, ATypeWithoutDefinitionIsRecordedAndSaidSo) {
  const std::string file = tempFile("unknown_type.mcap");
  RecordingWriter writer(file, {});
  bool unknown = false;
  const auto t = writer.addTopic({"/x", "someone_msgs/msg/Unknown", QosPreset::kControl}, &unknown);
  EXPECT_TRUE(unknown);
  writer.write(t, Time{1}, Time{1}, bytes(7));
  writer.close();
  Playback playback(file, {});
  EXPECT_EQ(playback.topics().at(0).type, "someone_msgs/msg/Unknown");
}

TEST(Recording, BadRecordingsAreRefusedNamingFileAndTopic) {
  const std::string file = tempFile("two_topics.mcap");
  {
    RecordingWriter writer(file, {});
    writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
    writer.addTopic({"/lidar/points", "sensor_msgs/msg/PointCloud2", QosPreset::kSensor});
  }
  try {
    Playback playback(file, {"/motor/state", "/lidar/pointz"});
    FAIL() << "a missing topic was accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find("no topic /lidar/pointz"), std::string::npos) << what;
    EXPECT_NE(what.find("/motor/state, /lidar/points"), std::string::npos) << what;
  }
  // Samples that are not CDR (another tool's JSON channel).
  const std::string json = tempFile("json.mcap");
  {
    mcap::Writer writer(json, {});
    const auto schema = writer.addSchema("x", "jsonschema", "{}");
    writer.addChannel(schema, "/j", "json");
  }
  try {
    Playback playback(json, {});
    FAIL() << "a JSON channel was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not as CDR"), std::string::npos) << e.what();
  }
  // Not a recording at all.
  const std::string text = tempFile("not_mcap.mcap");
  std::ofstream(text) << "hello";
  try {
    Playback playback(text, {});
    FAIL() << "a text file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(Recording, CompressionNames) {
  EXPECT_EQ(compressionByName("zstd"), mcap::Compression::kZstd);
  EXPECT_EQ(compressionByName("lz4"), mcap::Compression::kLz4);
  EXPECT_EQ(compressionByName("none"), mcap::Compression::kNone);
  EXPECT_THROW(compressionByName("gzip"), std::invalid_argument);
}

}  // namespace
}  // namespace uampc::recording
