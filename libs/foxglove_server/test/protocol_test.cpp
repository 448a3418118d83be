#include "uampc/foxglove/protocol.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace uampc::foxglove {
namespace {

using nlohmann::json;

TEST(FoxgloveProtocol, AdvertiseCarriesEverythingAClientDecodesWith) {
  const json j = json::parse(
      advertiseJson({{7, "/motor/state", "cdr", "sensor_msgs/msg/JointState", "float64[] velocity", "ros2msg"}}));
  EXPECT_EQ(j["op"], "advertise");
  ASSERT_EQ(j["channels"].size(), 1u);
  EXPECT_EQ(j["channels"][0]["id"], 7);
  EXPECT_EQ(j["channels"][0]["topic"], "/motor/state");
  EXPECT_EQ(j["channels"][0]["encoding"], "cdr");
  EXPECT_EQ(j["channels"][0]["schemaName"], "sensor_msgs/msg/JointState");
  EXPECT_EQ(j["channels"][0]["schemaEncoding"], "ros2msg");
}

TEST(FoxgloveProtocol, ServerInfoOffersTimeAndNothingToWrite) {
  const json j = json::parse(serverInfoJson("uampc", "42"));
  EXPECT_EQ(j["op"], "serverInfo");
  EXPECT_EQ(j["capabilities"], json::array({"time"}));
  EXPECT_EQ(j["sessionId"], "42");
}

TEST(FoxgloveProtocol, MessageDataFrameIsLittleEndian) {
  const std::uint8_t payload[] = {0xAA, 0xBB};
  const auto frame = messageDataFrame(0x01020304u, 0x1122334455667788ull, payload, 2);
  const std::vector<std::uint8_t> expected = {1,    0x04, 0x03, 0x02, 0x01, 0x88, 0x77, 0x66,
                                              0x55, 0x44, 0x33, 0x22, 0x11, 0xAA, 0xBB};
  EXPECT_EQ(frame, expected);
  EXPECT_EQ(timeFrame(1), (std::vector<std::uint8_t>{2, 1, 0, 0, 0, 0, 0, 0, 0}));
}

TEST(FoxgloveProtocol, ReadsSubscribeAndUnsubscribe) {
  const auto sub =
      parseClientRequest(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":5}]})");
  ASSERT_TRUE(std::holds_alternative<SubscribeRequest>(sub));
  const auto& s = std::get<SubscribeRequest>(sub).subscriptions;
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[1].id, 1u);
  EXPECT_EQ(s[1].channel, 5u);
  const auto unsub = parseClientRequest(R"({"op":"unsubscribe","subscriptionIds":[0,1]})");
  ASSERT_TRUE(std::holds_alternative<UnsubscribeRequest>(unsub));
  EXPECT_EQ(std::get<UnsubscribeRequest>(unsub).subscriptions, (std::vector<SubscriptionId>{0, 1}));
}

// Every malformed request is an answer, never an exception: the server turns it into a status error.
TEST(FoxgloveProtocol, MalformedRequestsAreNamedNotThrown) {
  const std::pair<const char*, const char*> cases[] = {
      {"{not json", "not valid JSON"},
      {"[1,2]", "string 'op'"},
      {R"({"op":5})", "string 'op'"},
      {R"({"op":"advertise","channels":[]})", "'advertise' is not served"},
      {R"({"op":"subscribe"})", "missing array 'subscriptions'"},
      {R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":3}]})", "'id' is not an unsigned"},
      {R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":4294967296}]})", "'channelId' is not an unsigned"},
      {R"({"op":"subscribe","subscriptions":[7]})", "missing 'id'"},
      {R"({"op":"unsubscribe","subscriptionIds":["a"]})", "subscriptionIds"},
  };
  for (const auto& [text, why] : cases) {
    const auto request = parseClientRequest(text);
    ASSERT_TRUE(std::holds_alternative<BadRequest>(request)) << text;
    EXPECT_NE(std::get<BadRequest>(request).message.find(why), std::string::npos)
        << text << " -> " << std::get<BadRequest>(request).message;
  }
}

TEST(FoxgloveProtocol, AnUnknownOpIsQuotedShort) {
  const std::string op(10000, 'x');
  const auto request = parseClientRequest(R"({"op":")" + op + R"("})");
  ASSERT_TRUE(std::holds_alternative<BadRequest>(request));
  EXPECT_LT(std::get<BadRequest>(request).message.size(), 200u);
}

TEST(FoxgloveProtocol, StatusSurvivesInvalidUtf8) {
  const json j = json::parse(statusJson(StatusLevel::kError, std::string("bad \xff byte")));
  EXPECT_EQ(j["level"], 2);
}

}  // namespace
}  // namespace uampc::foxglove
