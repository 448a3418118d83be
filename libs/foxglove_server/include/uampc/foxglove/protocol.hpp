// The messages of Foxglove's WebSocket protocol, subprotocol "foxglove.websocket.v1", that a
// read-only server needs: what it sends (serverInfo, status, advertise, unadvertise as JSON text;
// message data and time as binary frames) and what a client asks (subscribe, unsubscribe). Plain
// functions, no sockets: the server (server.hpp) and the tests share them. The protocol and what
// uampc serves with it: docs/user/viewing.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace uampc::foxglove {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

using ChannelId = std::uint32_t;
using SubscriptionId = std::uint32_t;

// One topic as a client sees it.
struct Channel {
  ChannelId id = 0;
  std::string topic;            // "/lidar/points"
  std::string encoding;         // "cdr" (ROS 2's)
  std::string schema_name;      // "sensor_msgs/msg/PointCloud2"
  std::string schema;           // the ros2msg definition
  std::string schema_encoding;  // "ros2msg"
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

// Server -> client, JSON text.
std::string serverInfoJson(const std::string& name, const std::string& session_id);
std::string statusJson(StatusLevel level, const std::string& message);
std::string advertiseJson(const std::vector<Channel>& channels);
std::string unadvertiseJson(const std::vector<ChannelId>& channel_ids);

// Server -> client, binary: opcode 1, subscription id, receive time (ns), payload; all little endian.
inline constexpr std::size_t kMessageDataHeaderBytes = 1 + 4 + 8;
// The part of a message data frame before its payload: all that differs between the subscriptions
// one message goes to, so that the payload is kept once and the header made at sending.
std::array<std::uint8_t, kMessageDataHeaderBytes> messageDataHeader(SubscriptionId subscription, std::uint64_t time_ns);
std::vector<std::uint8_t> messageDataFrame(SubscriptionId subscription, std::uint64_t time_ns,
                                           const std::uint8_t* payload, std::size_t size);
// Opcode 2: the server's current time (sim time when the domain has /clock).
std::vector<std::uint8_t> timeFrame(std::uint64_t time_ns);

// Client -> server.
struct Subscription {
  SubscriptionId id = 0;
  ChannelId channel = 0;
};
struct SubscribeRequest {
  std::vector<Subscription> subscriptions;
};
struct UnsubscribeRequest {
  std::vector<SubscriptionId> subscriptions;
};
// A request this server does not serve, or one it cannot read: `message` says which and why.
struct BadRequest {
  std::string message;
};
using ClientRequest = std::variant<SubscribeRequest, UnsubscribeRequest, BadRequest>;

// Reads one text message of a client. Never throws: malformed JSON, a missing or mistyped field,
// an unknown or unsupported op all come back as a BadRequest naming the problem.
ClientRequest parseClientRequest(const std::string& text);

}  // namespace uampc::foxglove
