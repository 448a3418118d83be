// `uampc play` announces what it will play: the samples of the topics it plays (after --topics,
// less the /clock it never plays) due at or after --start, and then plays that many. It used to
// announce the whole recording's count ("1 topics, 1856 samples" for --topics /tf, which played
// 1227).
#include <gtest/gtest.h>

#include <string>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/recording/recording_writer.hpp"

namespace uampc::test {
namespace {

SerializedMessage cdrBytes(std::uint8_t tag) {
  SerializedMessage m;
  m.data.assign(16, tag);
  m.data[0] = 0;  // CDR_LE encapsulation header
  m.data[1] = 1;
  return m;
}

// A lockstep recording, whose samples are due when they were published: /motor/state every 0.1 s
// and /clock with it, /tf every 0.2 s (published 0.2 i, logged 0.03 s later), and one more /tf
// published at 0.85 s and logged at 0.95 s, which --start 0.9 reads (its log time is past the
// start) but does not play (it was due before).
std::string writeRecording(const std::string& path) {
  using recording::RecordingWriter;
  RecordingWriter writer(path, {mcap::Compression::kZstd, 1024, recording::RecordingClock::kLockstep});
  const auto motor = writer.addTopic({"/motor/state", "sensor_msgs/msg/JointState", QosPreset::kControl});
  const auto clock = writer.addTopic({"/clock", "rosgraph_msgs/msg/Clock", QosPreset::kControl});
  const auto tf = writer.addTopic({"/tf", "tf2_msgs/msg/TFMessage", QosPreset::kControl});
  for (int i = 0; i < 20; ++i) {
    const Time t = Time::fromSeconds(0.1 * i);
    writer.write(clock, t, t, cdrBytes(1));
    writer.write(motor, t + Time::fromSeconds(0.01), t, cdrBytes(2));
    if (i % 2 == 0) writer.write(tf, t + Time::fromSeconds(0.03), t, cdrBytes(3));
    if (i == 9) writer.write(tf, Time::fromSeconds(0.95), Time::fromSeconds(0.85), cdrBytes(4));
  }
  writer.close();
  return path;
}

TEST(PlayCommand, AnnouncesTheSamplesItWillPlayAfterTopicsAndStart) {
  const std::string file = writeRecording(freshDirectory("play_count") + "/recording.mcap");
  const std::string play =
      "play " + file + " --rate 100 --domain " + std::to_string(testDomain(DomainBlock::kRecordReplay, 7));

  const CommandResult all = runUampc(play);
  ASSERT_EQ(all.exit_code, 0) << all.output;
  EXPECT_NE(all.output.find(": 2 topics, 31 samples, "), std::string::npos) << all.output;  // not /clock's 20
  EXPECT_NE(all.output.find("/motor/state, 20, "), std::string::npos) << all.output;
  EXPECT_NE(all.output.find("/tf, 11, "), std::string::npos) << all.output;

  // /tf due at 1.0, 1.2, 1.4, 1.6 and 1.8 s; not the one published at 0.85 s.
  const CommandResult tf = runUampc(play + " --topics /tf --start 0.9");
  ASSERT_EQ(tf.exit_code, 0) << tf.output;
  EXPECT_NE(tf.output.find(": 1 topics, 5 samples, "), std::string::npos) << tf.output;
  EXPECT_NE(tf.output.find("/tf, 5, "), std::string::npos) << tf.output;
}

}  // namespace
}  // namespace uampc::test
