// Recording and replay end to end (docs/user/topics-and-recordings.md): the default scene recorded
// by the recorder component is read by Foxglove's own MCAP reader, replayed into the LO with the
// same odometry as the live run, survives a SIGKILL of the recorder, and goes through uampc play
// and uampc record over DDS intact.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

struct Sample {
  std::uint64_t publish_time;
  std::vector<std::uint8_t> data;
  bool operator==(const Sample& o) const { return publish_time == o.publish_time && data == o.data; }
};

std::map<std::string, std::vector<Sample>> samplesByTopic(const std::string& file) {
  std::map<std::string, std::vector<Sample>> out;
  mcap::Reader reader(file);
  reader.forEachMessage({}, 0, [&](const mcap::MessageView& m) {
    out[m.channel->topic].push_back({m.publish_time, std::vector<std::uint8_t>(m.data, m.data + m.size)});
    return true;
  });
  return out;
}

// One recorded run of the default scene (4 s), shared by the tests.
class RecordReplay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_ = freshDirectory("record_default");
    const CommandResult r = runUampc("launch " + sourcePath("config/scenes/record_default.yaml") + " --out " + run_ +
                                     domainOverride(DomainBlock::kRecordReplay, 0) + " --set clock.duration=4");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static std::string recording() { return run_ + "/recording.mcap"; }
  static std::string run_;
};
std::string RecordReplay::run_;

TEST_F(RecordReplay, TheRecordingHoldsEveryTopicWithItsDefinition) {
  mcap::Reader reader(recording());
  EXPECT_FALSE(reader.recovered());
  std::map<std::string, std::string> types;
  for (const auto& channel : reader.channels()) {
    EXPECT_EQ(channel.message_encoding, "cdr") << channel.topic;
    EXPECT_TRUE(channel.metadata.count("offered_qos_profiles")) << channel.topic;
    for (const auto& schema : reader.schemas()) {
      if (schema.id == channel.schema_id) types[channel.topic] = schema.name;
    }
  }
  for (const auto& schema : reader.schemas()) {
    EXPECT_EQ(schema.encoding, "ros2msg");
    EXPECT_FALSE(schema.data.empty()) << schema.name;
  }
  EXPECT_EQ(types["/lidar/points"], "sensor_msgs/msg/PointCloud2");
  EXPECT_EQ(types["/motor/state"], "sensor_msgs/msg/JointState");
  EXPECT_EQ(types["/lo/odometry"], "nav_msgs/msg/Odometry");
  EXPECT_EQ(types["/tf"], "tf2_msgs/msg/TFMessage");
  EXPECT_EQ(types["/tf_static"], "tf2_msgs/msg/TFMessage");
  const auto samples = samplesByTopic(recording());
  // 200 Hz encoder states and 10 Hz scans over 4 s (the last step's samples are never delivered).
  EXPECT_NEAR(static_cast<double>(samples.at("/motor/state").size()), 800.0, 2.0);
  EXPECT_NEAR(static_cast<double>(samples.at("/lidar/points").size()), 40.0, 2.0);
  EXPECT_EQ(samples.at("/tf_static").size(), 1u);
}

TEST_F(RecordReplay, FoxglovesReaderDecodesEveryRecordedMessage) {
  if (const char* skip = std::getenv("UAMPC_SKIP_JS"); skip && std::string(skip) == "1") GTEST_SKIP();
  const CommandResult r =
      runShell("node " + sourcePath("tests/mcap_js/read_mcap.mjs") + " " + recording() + " | tail -n 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  mcap::Reader reader(recording());
  EXPECT_NE(r.output.find("\"messages\":\"" + std::to_string(reader.messageCount()) + "\""), std::string::npos)
      << r.output;
}

TEST_F(RecordReplay, ReplayingTheRecordingIntoTheLoGivesTheRecordedOdometry) {
  const std::string replay = freshDirectory("replay_lo");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/replay_lo_recorded.yaml") + " --out " + replay +
                                   domainOverride(DomainBlock::kRecordReplay, 1) +
                                   " --set clock.duration=4 --set player.file=" + recording());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto live = samplesByTopic(recording());
  const auto replayed = samplesByTopic(replay + "/replay.mcap");
  for (const char* topic : {"/lo/odometry", "/lo/registered"}) {
    ASSERT_GE(live.at(topic).size(), 35u) << topic;
    EXPECT_TRUE(live.at(topic) == replayed.at(topic)) << topic << ": the replayed LO's samples differ";
  }
  EXPECT_EQ(readFile(run_ + "/estimate.tum"), readFile(replay + "/estimate.tum"));
}

TEST_F(RecordReplay, ARecordingWithoutTheTopicsAsceneNeedsIsRefusedByName) {
  // With a recording that has them, the shipped scene is valid and says no warning.
  const CommandResult valid =
      runUampc("validate " + sourcePath("config/scenes/replay_lo.yaml") + " --set player.file=" + recording());
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  EXPECT_EQ(startWarnings(valid.output), "") << valid.output;
  const CommandResult missing = runUampc("validate " + sourcePath("config/scenes/replay_lo.yaml") +
                                         " --set player.file=" + recording() + " --set player.topics=[/lidar/pointz]");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find(recording() + ": the recording has no topic /lidar/pointz (it has: "),
            std::string::npos)
      << missing.output;
  // A file that does not exist is one error, about the parameter (the player is not asked for ports).
  const CommandResult absent =
      runUampc("validate " + sourcePath("config/scenes/replay_lo.yaml") + " --set player.file=/nonexistent.mcap");
  EXPECT_EQ(absent.exit_code, 2) << absent.output;
  EXPECT_NE(absent.output.find("file not found: /nonexistent.mcap"), std::string::npos) << absent.output;
  EXPECT_EQ(absent.output.find("map::at"), std::string::npos) << absent.output;
  const std::string text = sourcePath("config/scenes/replay_lo.yaml");
  const CommandResult not_mcap = runUampc("validate " + text + " --set player.file=" + text);
  EXPECT_EQ(not_mcap.exit_code, 2) << not_mcap.output;
  EXPECT_NE(not_mcap.output.find("cannot read the recording: " + text), std::string::npos) << not_mcap.output;
}

TEST_F(RecordReplay, PlayAndRecordCommandsCarryEverySampleOverDds) {
  const std::string out = freshDirectory("play_record");
  const std::string copy = out + "/copy.mcap";
  // The recorder first; play waits until it hears every topic, and the recorder stops at Ctrl-C.
  const CommandResult r = runShell(
      binaryPath("bin/uampc") + " record --domain " + std::to_string(testDomain(DomainBlock::kRecordReplay, 2)) +
      " -o " + copy + " /motor/state /tf_static /lo/odometry > " + out + "/record.log 2>&1 & rec=$!; " +
      binaryPath("bin/uampc") + " play " + recording() + " --domain " +
      std::to_string(testDomain(DomainBlock::kRecordReplay, 2)) +
      " --wait-for-readers --topics /motor/state /tf_static /lo/odometry; played=$?; sleep 1; "
      "kill -INT $rec; wait $rec; recorded=$?; cat " +
      out + "/record.log; echo \"played=$played recorded=$recorded\"");
  ASSERT_NE(r.output.find("played=0 recorded=0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("publish ms mean / max"), std::string::npos) << r.output;  // play reports its costs
  const auto original = samplesByTopic(recording());
  const auto copied = samplesByTopic(copy);
  for (const char* topic : {"/motor/state", "/tf_static", "/lo/odometry"}) {
    ASSERT_TRUE(copied.count(topic)) << topic << "\n" << r.output;
    ASSERT_EQ(copied.at(topic).size(), original.at(topic).size()) << topic;
    for (std::size_t i = 0; i < copied.at(topic).size(); ++i) {
      // The bytes travel unchanged; the publish time is now the player's wall clock.
      EXPECT_EQ(copied.at(topic)[i].data, original.at(topic)[i].data) << topic << " sample " << i;
    }
  }
}

// A recording of one run played onto the domain of another, live (docs/decisions/replay-leaves-lockstep-topics.md):
// `uampc record` leaves the lockstep protocol's topics out unless they are named, `uampc play` never
// publishes them nor a recorded /clock, and the live run goes on to its end (it used to stop, taking
// the played protocol for another lockstep run).
TEST_F(RecordReplay, APlayOnTheDomainOfALiveRunLeavesTheRunAlone) {
  const std::string out = freshDirectory("play_beside_a_run");
  const std::string scene = sourcePath("tests/scenes/motor_constant_speed.yaml") + " --set clock.real_time_factor=1";
  const std::string recorded_domain = std::to_string(testDomain(DomainBlock::kRecordReplay, 5));
  const pid_t recorded =
      startLaunch(scene + " --set clock.duration=5 --out " + out + "/recorded --set domain_id=" + recorded_domain,
                  out + "/recorded.log");
  // The recorders and the player join runs that are already stepping, as in the reported case.
  const auto stepping = [](const std::string& log) { return [log] { return logHas(log, "uampc: sim "); }; };
  ASSERT_TRUE(waitFor(stepping(out + "/recorded.log"), std::chrono::seconds(30))) << readFile(out + "/recorded.log");
  const std::string record =
      binaryPath("bin/uampc") + " record --domain " + recorded_domain + " --duration 3 -o " + out;
  const CommandResult recording =
      runShell(record + "/named.mcap /clock /uampc/lockstep/progress /motor/state > " + out + "/named.log 2>&1 & " +
               record + "/all.mcap > " + out + "/all.log 2>&1; wait; cat " + out + "/named.log " + out + "/all.log");
  ASSERT_EQ(exitCodeOf(recorded), 0) << readFile(out + "/recorded.log");
  const auto all = samplesByTopic(out + "/all.mcap");
  EXPECT_TRUE(all.count("/motor/state")) << recording.output;
  for (const auto& [topic, samples] : all) EXPECT_NE(topic.rfind("/uampc/lockstep/", 0), 0u) << topic;
  ASSERT_TRUE(samplesByTopic(out + "/named.mcap").count("/uampc/lockstep/progress")) << recording.output;

  const std::string live_domain = std::to_string(testDomain(DomainBlock::kRecordReplay, 6));
  const pid_t live = startLaunch(
      scene + " --set clock.duration=8 --out " + out + "/live --set domain_id=" + live_domain, out + "/live.log");
  ASSERT_TRUE(waitFor(stepping(out + "/live.log"), std::chrono::seconds(30))) << readFile(out + "/live.log");
  const CommandResult play = runUampc("play " + out + "/named.mcap --domain " + live_domain);
  EXPECT_EQ(play.exit_code, 0) << play.output;
  EXPECT_NE(play.output.find("not playing /uampc/lockstep/progress"), std::string::npos) << play.output;
  EXPECT_NE(play.output.find("not playing /clock"), std::string::npos) << play.output;
  EXPECT_EQ(exitCodeOf(live), 0) << readFile(out + "/live.log");
}

TEST_F(RecordReplay, ARecorderKilledMidRunLeavesItsCompleteChunksReadable) {
  const std::string out = freshDirectory("killed_recorder");
  const std::string file = out + "/recording.mcap";
  // Its own session, so that the launcher and its processes are killed together, as by a power cut
  // (sh's kill takes -PID as the group; clock.duration bounds the run if the kill went wrong).
  const CommandResult r = runShell(
      "setsid " + binaryPath("bin/uampc") + " launch " + sourcePath("config/scenes/record_default.yaml") + " --out " +
      out + domainOverride(DomainBlock::kRecordReplay, 3) +
      " --set clock.duration=60 --set recorder.chunk_size=262144 > " + out +
      "/run.log 2>&1 & pid=$!; for i in $(seq 600); do [ $(stat -c %s " + file +
      " 2>/dev/null || echo 0) -gt 15000000 ] && break; sleep 0.1; done; kill -KILL -$pid; wait $pid; echo killed");
  ASSERT_NE(r.output.find("killed"), std::string::npos) << r.output;
  mcap::Reader reader(file);
  EXPECT_TRUE(reader.recovered());
  EXPECT_GT(reader.messageCount(), 100u);  // 15 MB: past the world's mesh, into the scans
  // The player plays what was saved, saying the file was damaged.
  const CommandResult replay =
      runUampc("launch " + sourcePath("config/scenes/replay_lo.yaml") + domainOverride(DomainBlock::kRecordReplay, 4) +
               " --set clock.duration=1 --set player.file=" + file);
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_NE(replay.output.find("WARN"), std::string::npos) << replay.output;
}

}  // namespace
}  // namespace uampc::test
