// A serialized sample (CDR with its encapsulation, as recordings and serialized ports carry it)
// to and from a compiled-in message type, through the type's own fastddsgen support.
#pragma once

#include <cstring>
#include <stdexcept>
#include <vector>

#include "uampc/runtime/message_type.hpp"
#include "uampc/runtime/serialized_message.hpp"

namespace uampc {

// False when the bytes are not a sample of this type.
template <typename Message>
bool decodeSample(const SerializedMessage& sample, Message& message) {
  typename MessageType<Message>::PubSubType support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(sample.data.size()));
  std::memcpy(payload.data, sample.data.data(), sample.data.size());
  payload.length = static_cast<std::uint32_t>(sample.data.size());
  return support.deserialize(&payload, &message);
}

template <typename Message>
SerializedMessage encodeSample(Message& message) {
  typename MessageType<Message>::PubSubType support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(support.getSerializedSizeProvider(&message)());
  if (!support.serialize(&message, &payload)) throw std::runtime_error("a sample that does not encode");
  return SerializedMessage{std::vector<std::uint8_t>(payload.data, payload.data + payload.length)};
}

}  // namespace uampc
