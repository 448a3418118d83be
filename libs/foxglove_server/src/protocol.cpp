#include "uampc/foxglove/protocol.hpp"

#include <nlohmann/json.hpp>

#include <limits>

namespace uampc::foxglove {

using nlohmann::json;

namespace {

void appendLittleEndian(std::vector<std::uint8_t>& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

// A JSON number that is an unsigned 32-bit integer (ids are), else throws with the field's name.
std::uint32_t idField(const json& object, const char* field) {
  if (!object.is_object() || !object.contains(field))
    throw std::invalid_argument(std::string("missing '") + field + "'");
  const json& value = object.at(field);
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument(std::string("'") + field + "' is not an unsigned 32-bit integer");
  }
  return value.get<std::uint32_t>();
}

const json& arrayField(const json& object, const char* field) {
  if (!object.contains(field) || !object.at(field).is_array()) {
    throw std::invalid_argument(std::string("missing array '") + field + "'");
  }
  return object.at(field);
}

ClientRequest readSubscribe(const json& message) {
  SubscribeRequest request;
  for (const json& s : arrayField(message, "subscriptions")) {
    request.subscriptions.push_back({idField(s, "id"), idField(s, "channelId")});
  }
  return request;
}

ClientRequest readUnsubscribe(const json& message) {
  UnsubscribeRequest request;
  for (const json& id : arrayField(message, "subscriptionIds")) {
    if (!id.is_number_unsigned() || id.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
      throw std::invalid_argument("'subscriptionIds' holds something other than unsigned 32-bit integers");
    }
    request.subscriptions.push_back(id.get<std::uint32_t>());
  }
  return request;
}

}  // namespace

std::string serverInfoJson(const std::string& name, const std::string& session_id) {
  // "time": the server sends its clock (sim time in a lockstep run) so that the client's time
  // follows the run, not the wall clock. No client publishing, parameters or services: a viewer
  // only reads (docs/decisions/live-viewer.md).
  return json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", json::array({"time"})},
              {"supportedEncodings", json::array()},
              {"metadata", json::object()},
              {"sessionId", session_id}}
      .dump();
}

std::string statusJson(StatusLevel level, const std::string& message) {
  // Replacement of invalid UTF-8: a message may quote what a client sent.
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

std::string advertiseJson(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string unadvertiseJson(const std::vector<ChannelId>& channel_ids) {
  return json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::array<std::uint8_t, kMessageDataHeaderBytes> messageDataHeader(SubscriptionId subscription,
                                                                    std::uint64_t time_ns) {
  std::array<std::uint8_t, kMessageDataHeaderBytes> header{};
  header[0] = 1;
  for (int i = 0; i < 4; ++i) header[1 + i] = static_cast<std::uint8_t>(subscription >> (8 * i));
  for (int i = 0; i < 8; ++i) header[5 + i] = static_cast<std::uint8_t>(time_ns >> (8 * i));
  return header;
}

std::vector<std::uint8_t> messageDataFrame(SubscriptionId subscription, std::uint64_t time_ns,
                                           const std::uint8_t* payload, std::size_t size) {
  const auto header = messageDataHeader(subscription, time_ns);
  std::vector<std::uint8_t> frame(header.begin(), header.end());
  frame.insert(frame.end(), payload, payload + size);
  return frame;
}

std::vector<std::uint8_t> timeFrame(std::uint64_t time_ns) {
  std::vector<std::uint8_t> frame{2};
  appendLittleEndian(frame, time_ns, 8);
  return frame;
}

ClientRequest parseClientRequest(const std::string& text) {
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) return BadRequest{"not valid JSON"};
  if (!message.is_object() || !message.contains("op") || !message.at("op").is_string()) {
    return BadRequest{"not a JSON object with a string 'op'"};
  }
  // Quoted back in the answer: cut, so that a client cannot make the server echo megabytes.
  const std::string op = message.at("op").get<std::string>().substr(0, 64);
  try {
    if (op == "subscribe") return readSubscribe(message);
    if (op == "unsubscribe") return readUnsubscribe(message);
  } catch (const std::invalid_argument& e) {
    return BadRequest{op + ": " + e.what()};
  }
  return BadRequest{"op '" + op + "' is not served (a read-only server: subscribe and unsubscribe only)"};
}

}  // namespace uampc::foxglove
