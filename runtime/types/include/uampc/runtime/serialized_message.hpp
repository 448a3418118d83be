// Samples of any message type, kept as the bytes that travel on the wire: for the parts of uampc
// that move samples without knowing their type (recorder, player, topic tools).
#pragma once

#include <fastdds/dds/topic/TopicDataType.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace uampc {

// One sample as CDR, with the 4-byte encapsulation header first: exactly the DDS payload, and
// exactly what a rosbag2 MCAP file stores as a message with encoding "cdr".
struct SerializedMessage {
  std::vector<std::uint8_t> data;
};

// Fast DDS type support that keeps samples serialized. It is registered under the real type's DDS
// name (dds_names.hpp), so it matches writers and readers of that type, ours and other vendors'
// (matching is by type name: uampc's types carry no TypeObject).
class SerializedTypeSupport : public eprosima::fastdds::dds::TopicDataType {
 public:
  // max_serialized_size: a hint for Fast DDS's preallocation (the real type support's m_typeSize
  // when known); larger samples are still carried.
  explicit SerializedTypeSupport(const std::string& dds_type_name, std::uint32_t max_serialized_size = 1024);
  // Sized like the real type's support when this process has the type registered, else with the
  // default hint: what every serialized reader and writer of uampc uses.
  static SerializedTypeSupport* forDdsType(const std::string& dds_type_name);

  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5) override;
};

}  // namespace uampc
