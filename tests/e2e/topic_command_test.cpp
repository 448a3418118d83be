// `uampc topic list | echo | hz | bw` against a small publisher in this test, on a DDS domain of the
// test's own: the topics, types and writer counts it creates, the values it publishes, its rate and
// its sample size are known here, and the command must find them. Also: the message definition and
// decoding of a user's IDL package (uampc_test_msgs/Ping, which this test links and the uampc
// command does not), and the hz/bw figures on known arrival times.
#include <gtest/gtest.h>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "topic/topic_statistics.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/std_msgs.hpp"
#include "uampc/msgs/uampc_test_msgs.hpp"
#include "uampc/runtime/cdr_decoder.hpp"
#include "uampc/runtime/message_definition.hpp"

namespace uampc::test {
namespace {

using namespace eprosima::fastdds::dds;

constexpr int kDomain = testDomain(DomainBlock::kTopicTools, 0);
constexpr double kRateHz = 20.0;
const std::string kDomainOption = " --domain " + std::to_string(kDomain);

// The samples this test publishes.
sensor_msgs::msg::JointState jointState() {
  sensor_msgs::msg::JointState m;
  m.header().stamp().sec(12);
  m.header().stamp().nanosec(500);
  m.header().frame_id("base_link");
  m.name({"motor"});
  m.position({0.1, -2.5});
  m.velocity({3.6});
  return m;
}

uampc_test_msgs::msg::Ping ping() {
  uampc_test_msgs::msg::Ping m;
  m.count(7);
  m.text("ping");
  return m;
}

// A DDS participant of this test: /test/joints (JointState, two writers, one publishing),
// /test/rate (Float64 at kRateHz, one writer, one reader), /test/ping (Ping, a type the uampc
// command does not know) and plain_topic (a DDS topic that is no ROS topic), all published at kRateHz.
class TestPublisher {
 public:
  TestPublisher() {
    DomainParticipantQos qos = DomainParticipantFactory::get_instance()->get_default_participant_qos();
    qos.name("topic test publisher");
    participant_ = DomainParticipantFactory::get_instance()->create_participant(kDomain, qos);
    publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
    joints_ = writer<sensor_msgs::msg::JointState>("rt/test/joints");
    writer<sensor_msgs::msg::JointState>("rt/test/joints");  // a second writer, which never writes
    rate_ = writer<std_msgs::msg::Float64>("rt/test/rate");
    subscriber_->create_datareader(topics_.at("rt/test/rate"), DATAREADER_QOS_DEFAULT);
    ping_ = writer<uampc_test_msgs::msg::Ping>("rt/test/ping");
    plain_ = writer<std_msgs::msg::Float64>("plain_topic");
    thread_ = std::thread([this] { publish(); });
  }

  ~TestPublisher() {
    stop_ = true;
    thread_.join();
    participant_->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }

 private:
  template <typename Message>
  DataWriter* writer(const std::string& topic_name) {
    TypeSupport support(new typename MessageType<Message>::PubSubType());
    support.register_type(participant_);
    if (!topics_.count(topic_name)) {
      topics_[topic_name] = participant_->create_topic(topic_name, support.get_type_name(), TOPIC_QOS_DEFAULT);
    }
    return publisher_->create_datawriter(topics_.at(topic_name), DATAWRITER_QOS_DEFAULT);
  }

  void publish() {
    sensor_msgs::msg::JointState joints = jointState();
    uampc_test_msgs::msg::Ping p = ping();
    std_msgs::msg::Float64 value;
    value.data(0.25);
    auto next = std::chrono::steady_clock::now();
    while (!stop_) {
      joints_->write(&joints);
      rate_->write(&value);
      ping_->write(&p);
      plain_->write(&value);
      next +=
          std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1 / kRateHz));
      std::this_thread::sleep_until(next);
    }
  }

  DomainParticipant* participant_ = nullptr;
  Publisher* publisher_ = nullptr;
  Subscriber* subscriber_ = nullptr;
  std::map<std::string, Topic*> topics_;
  DataWriter* joints_ = nullptr;
  DataWriter* rate_ = nullptr;
  DataWriter* ping_ = nullptr;
  DataWriter* plain_ = nullptr;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// The commands run with their default discovery wait (3.5 s, topic_command.hpp), or longer: on this
// machine a first discovery takes up to 2.9 s now and then, and a test must not depend on luck.
class TopicCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { publisher_ = new TestPublisher(); }
  static void TearDownTestSuite() { delete publisher_; }
  static TestPublisher* publisher_;
};
TestPublisher* TopicCommand::publisher_ = nullptr;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++count;
  return count;
}

// The words of the line of `list` that starts with `topic`; empty when there is none.
std::vector<std::string> listLine(const std::string& output, const std::string& topic) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    if (!w.empty() && w[0] == topic) return w;
  }
  return {};
}

TEST_F(TopicCommand, ListShowsEveryTopicWithItsTypeAndWriterAndReaderCounts) {
  const CommandResult r = runUampc("topic list" + kDomainOption);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  using Words = std::vector<std::string>;
  EXPECT_EQ(listLine(r.output, "/test/joints"),
            (Words{"/test/joints", "sensor_msgs/msg/JointState", "writers:", "2", "readers:", "0"}))
      << r.output;
  EXPECT_EQ(listLine(r.output, "/test/rate"),
            (Words{"/test/rate", "std_msgs/msg/Float64", "writers:", "1", "readers:", "1"}))
      << r.output;
  EXPECT_EQ(listLine(r.output, "/test/ping"),
            (Words{"/test/ping", "uampc_test_msgs/msg/Ping", "writers:", "1", "readers:", "0"}))
      << r.output;
  // A DDS topic outside ROS's naming keeps its DDS name.
  EXPECT_EQ(listLine(r.output, "plain_topic"),
            (Words{"plain_topic", "std_msgs/msg/Float64", "writers:", "1", "readers:", "0"}))
      << r.output;
}

TEST_F(TopicCommand, VerboseListNamesEachEndpointsParticipantAndVendor) {
  const CommandResult r = runUampc("topic list -v" + kDomainOption);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::regex writer(
      R"(\n    writer  'topic test publisher' [0-9a-f]{2}(\.[0-9a-f]{2}){11}  vendor 01\.0f \(eProsima Fast DDS\)  reliable, transient-local\n)");
  EXPECT_TRUE(std::regex_search(r.output, writer)) << r.output;
  // Fast DDS's default QoS: writers reliable and transient-local, readers best-effort and volatile.
  EXPECT_TRUE(contains(r.output, "\n    reader  'topic test publisher' ")) << r.output;
  EXPECT_TRUE(contains(r.output, "(eProsima Fast DDS)  best-effort, volatile\n")) << r.output;
}

TEST_F(TopicCommand, ListShowsAnotherVendorsEndpoints) {
  // The wire-format test's Cyclone DDS subscriber reads two topics (its participant has no name); it
  // is stopped once the list is printed, so that it outlives neither the list nor this test.
  const CommandResult r = runShell(binaryPath("tests/cyclone_subscriber") + " " + std::to_string(kDomain) +
                                   " 30 > /dev/null 2>&1 & cyclone=$!; " + binaryPath("bin/uampc") + " topic list -v" +
                                   kDomainOption + "; status=$?; kill $cyclone; wait $cyclone; exit $status");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(
      listLine(r.output, "/wire_test/points"),
      (std::vector<std::string>{"/wire_test/points", "sensor_msgs/msg/PointCloud2", "writers:", "0", "readers:", "1"}))
      << r.output;
  const std::regex reader(
      R"(\n    reader  \(unnamed\) [0-9a-f]{2}(\.[0-9a-f]{2}){11}  vendor 01\.10 \(Eclipse Cyclone DDS\)  reliable, volatile\n)");
  EXPECT_TRUE(std::regex_search(r.output, reader)) << r.output;
}

TEST_F(TopicCommand, EchoPrintsADecodedSampleAsYaml) {
  const CommandResult r = runUampc("topic echo /test/joints -n 1" + kDomainOption);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output,
                       "header:\n"
                       "  stamp:\n"
                       "    sec: 12\n"
                       "    nanosec: 500\n"
                       "  frame_id: base_link\n"
                       "name: [motor]\n"
                       "position: [0.1, -2.5]\n"
                       "velocity: [3.6]\n"
                       "effort: []\n"
                       "---\n"))
      << r.output;
  EXPECT_EQ(occurrences(r.output, "---\n"), 1) << r.output;
}

TEST_F(TopicCommand, TheDomainIsRosDomainIdWhenNoneIsGiven) {
  const CommandResult r = runShell("ROS_DOMAIN_ID=" + std::to_string(kDomain) + " " + binaryPath("bin/uampc") +
                                   " topic echo /test/joints -n 1");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "frame_id: base_link\n")) << r.output;
}

TEST_F(TopicCommand, EchoOfATypeItDoesNotKnowPrintsSizes) {
  const CommandResult r = runUampc("topic echo /test/ping -n 2" + kDomainOption);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "type uampc_test_msgs/msg/Ping is not known")) << r.output;
  // 4 (CDR header) + 8 (count) + 4 (text's length) + 5 ("ping" and its NUL) = 21 bytes of CDR, which
  // Fast DDS pads to a multiple of 4 on the wire: the payload a reader gets.
  EXPECT_TRUE(contains(r.output, "<24 bytes>\n---\n<24 bytes>\n---\n")) << r.output;
}

TEST_F(TopicCommand, HzMeasuresThePublishedRate) {
  const CommandResult r = runShell("timeout --preserve-status -s INT 7 " + binaryPath("bin/uampc") +
                                   " topic hz /test/rate" + kDomainOption);
  EXPECT_EQ(r.exit_code, 0) << "Ctrl-C ends it with 0:\n" << r.output;
  const std::regex report(
      R"(average rate: ([0-9.]+)\n\tmin: [0-9.]+s max: [0-9.]+s std dev: [0-9.]+s window: (\d+)\n)");
  std::vector<double> rates;
  for (std::sregex_iterator it(r.output.begin(), r.output.end(), report), end; it != end; ++it) {
    rates.push_back(std::stod((*it)[1]));
  }
  ASSERT_GE(rates.size(), 2u) << "a report each second and one at Ctrl-C:\n" << r.output;
  // A measurement of the publisher's sleep_until loop, not of uampc's timing: a generous bound.
  EXPECT_NEAR(rates.back(), kRateHz, 0.2 * kRateHz) << r.output;
}

TEST_F(TopicCommand, BwReportsTheSampleSizeExactly) {
  const CommandResult r = runShell("timeout --preserve-status -s INT 6 " + binaryPath("bin/uampc") +
                                   " topic bw /test/rate" + kDomainOption);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // A Float64: the 4-byte CDR header and 8 bytes.
  EXPECT_TRUE(contains(r.output, " messages\n\tMessage size mean: 12 B min: 12 B max: 12 B\n")) << r.output;
}

TEST_F(TopicCommand, AnUnknownTopicIsNamedWithTheClosestOneFound) {
  const CommandResult r = runUampc("topic hz /test/joint --wait 4" + kDomainOption);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "no writer of /test/joint found on domain " + std::to_string(kDomain) +
                                     " within 4 s; did you mean /test/joints?"))
      << r.output;
}

TEST(TopicCommandLine, EachActionHasHelpWithItsOptions) {
  const std::map<std::string, std::vector<std::string>> options = {
      {"list", {"--domain N", "--wait S", "-v,--verbose"}},
      {"echo", {"TOPIC", "--domain N", "--wait S", "-n N", "--full"}},
      {"hz", {"TOPIC", "--domain N", "--wait S", "--window N"}},
      {"bw", {"TOPIC", "--domain N", "--wait S", "--window N"}}};
  for (const auto& [action, names] : options) {
    const CommandResult r = runUampc("topic " + action + " --help");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "usage: uampc topic " + action)) << r.output;
    for (const std::string& name : names) EXPECT_TRUE(contains(r.output, "  " + name)) << action << ": " << name;
  }
  EXPECT_EQ(runUampc("topic").exit_code, 2);
  EXPECT_EQ(runUampc("topic echo").exit_code, 2);
  EXPECT_EQ(runUampc("topic list --domain 300").exit_code, 2);
  const CommandResult bad_env = runShell("ROS_DOMAIN_ID=abc " + binaryPath("bin/uampc") + " topic list --wait 0");
  EXPECT_EQ(bad_env.exit_code, 2) << bad_env.output;
  EXPECT_TRUE(contains(bad_env.output, "ROS_DOMAIN_ID is 'abc'")) << bad_env.output;
}

// ---- a user's IDL package ----

TEST(UserMessageType, HasADefinitionAndDecodes) {
  EXPECT_EQ(messageDefinition("uampc_test_msgs/msg/Ping"), "uint64 count\nstring text\n");
  uampc_test_msgs::msg::Ping m = ping();
  uampc_test_msgs::msg::PingPubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&m)());
  ASSERT_TRUE(type.serialize(&m, &payload));
  const std::optional<MessageStructure> structure = findMessageStructure("uampc_test_msgs/msg/Ping");
  ASSERT_TRUE(structure.has_value());
  const DecodedValue v = decodeCdr(*structure, payload.data, payload.length);
  EXPECT_EQ(v["count"].scalar.unsigned_value, 7u);
  EXPECT_EQ(v["text"].text, "ping");
}

// ---- the hz and bw figures ----

TEST(TopicStatistics, RateAndPeriodsAsRos2TopicHzComputesThem) {
  app::TopicStatistics s(10);
  EXPECT_FALSE(s.hasRate());
  const double times[] = {0.0, 0.1, 0.3, 0.4};
  const std::size_t sizes[] = {10, 20, 30, 40};
  for (int i = 0; i < 4; ++i) s.add(times[i], sizes[i]);
  ASSERT_TRUE(s.hasRate());
  EXPECT_DOUBLE_EQ(s.rateHz(), 3.0 / 0.4);
  EXPECT_DOUBLE_EQ(s.minPeriodS(), 0.1);
  EXPECT_DOUBLE_EQ(s.maxPeriodS(), 0.2);
  const double mean = 0.4 / 3.0;
  EXPECT_NEAR(s.periodStdDevS(), std::sqrt((2 * std::pow(0.1 - mean, 2) + std::pow(0.2 - mean, 2)) / 3.0), 1e-15);
  EXPECT_DOUBLE_EQ(s.meanBytes(), 25.0);
  EXPECT_EQ(s.minBytes(), 10u);
  EXPECT_EQ(s.maxBytes(), 40u);
  EXPECT_DOUBLE_EQ(s.bytesPerSecond(), 25.0 * 7.5);
  EXPECT_EQ(s.bwReport(), "187.50 B/s from 4 messages\n\tMessage size mean: 25 B min: 10 B max: 40 B\n");
  EXPECT_EQ(s.hzReport(), "average rate: 7.500\n\tmin: 0.100s max: 0.200s std dev: 0.04714s window: 4\n");
}

TEST(TopicStatistics, TheWindowKeepsTheLatestSamples) {
  app::TopicStatistics s(3);
  for (int i = 0; i < 5; ++i) s.add(i * 0.5 + (i == 4 ? 0.5 : 0.0), 100 * (i + 1));  // the last period is 1 s
  EXPECT_EQ(s.samples(), 3u);
  EXPECT_EQ(s.received(), 5u);
  EXPECT_DOUBLE_EQ(s.rateHz(), 2.0 / 1.5);  // periods 0.5 and 1.0 of the last three
  EXPECT_EQ(s.minBytes(), 300u);
}

TEST(TopicStatistics, BytesInRos2TopicBwsUnits) {
  EXPECT_EQ(app::formatBytes(12), "12 B");
  EXPECT_EQ(app::formatBytes(12.5), "12.50 B");
  EXPECT_EQ(app::formatBytes(1234), "1.23 KB");
  EXPECT_EQ(app::formatBytes(4.56e6), "4.56 MB");
}

}  // namespace
}  // namespace uampc::test
