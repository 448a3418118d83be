#include "uampc/runtime/serialized_message.hpp"

#include <cstring>
#include <memory>

#include "uampc/runtime/cdr_decoder.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/message_type.hpp"

namespace uampc {

using eprosima::fastrtps::rtps::InstanceHandle_t;
using eprosima::fastrtps::rtps::SerializedPayload_t;


SerializedTypeSupport::SerializedTypeSupport(const std::string& dds_type_name, std::uint32_t max_serialized_size) {
  setName(dds_type_name.c_str());
  m_typeSize = max_serialized_size;
  m_isGetKeyDefined = false;  // ROS 2 types have no keys
  auto_fill_type_object(false);
  auto_fill_type_information(false);
}

SerializedTypeSupport* SerializedTypeSupport::forDdsType(const std::string& dds_type_name) {
  const std::string ros_type = rosTypeName(dds_type_name);
  if (const MessageTypeInfo* known = ros_type.empty() ? nullptr : findMessageType(ros_type)) {
    const std::unique_ptr<TopicDataType> real(known->make_type_support());
    return new SerializedTypeSupport(dds_type_name, real->m_typeSize);
  }
  return new SerializedTypeSupport(dds_type_name);
}

bool SerializedTypeSupport::serialize(void* data, SerializedPayload_t* payload) {
  const auto& bytes = static_cast<SerializedMessage*>(data)->data;
  if (bytes.size() < kCdrEncapsulationSize) return false;  // not CDR: refuse rather than send garbage
  payload->reserve(static_cast<std::uint32_t>(bytes.size()));
  std::memcpy(payload->data, bytes.data(), bytes.size());
  payload->length = static_cast<std::uint32_t>(bytes.size());
  // Byte 1 of the header is the representation's low byte: odd for little-endian (CDR_LE, PL_CDR_LE).
  payload->encapsulation = (bytes[1] & 1) ? CDR_LE : CDR_BE;
  return true;
}

bool SerializedTypeSupport::deserialize(SerializedPayload_t* payload, void* data) {
  auto& bytes = static_cast<SerializedMessage*>(data)->data;
  bytes.assign(payload->data, payload->data + payload->length);
  return payload->length >= kCdrEncapsulationSize;
}

std::function<std::uint32_t()> SerializedTypeSupport::getSerializedSizeProvider(void* data) {
  return [data] { return static_cast<std::uint32_t>(static_cast<SerializedMessage*>(data)->data.size()); };
}

void* SerializedTypeSupport::createData() { return new SerializedMessage(); }

void SerializedTypeSupport::deleteData(void* data) { delete static_cast<SerializedMessage*>(data); }

bool SerializedTypeSupport::getKey(void*, InstanceHandle_t*, bool) { return false; }

}  // namespace uampc
