// One Fast DDS participant, with its topics and registered types, and the translation from our QoS
// presets and ROS 2 topic names to DDS (docs/dev/architecture.md section 4): a scene's process has
// one (and one more for its serialized ports), `uampc play` and `uampc record` one each.
#pragma once

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <functional>
#include <map>
#include <string>

#include "uampc/runtime/component.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/dds_security.hpp"
#include "uampc/runtime/qos.hpp"

namespace uampc {

// The writer QoS a preset means (docs/dev/architecture.md section 4): in lockstep every stream is
// reliable and keeps every sample. Readers get the same reliability, durability and history.
eprosima::fastdds::dds::DataWriterQos writerQosOf(QosPreset preset, bool lockstep);

// Makes a new type support; DdsNode registers it once per type.
using TypeSupportMaker = std::function<eprosima::fastdds::dds::TopicDataType*()>;

class DdsNode {
 public:
  // profile_file: Fast DDS XML profiles loaded before the participant is made (may be empty).
  // identity: the DDS Security files it authenticates with (dds_security.hpp); none: security off.
  DdsNode(int domain_id, const std::string& profile_file, bool lockstep, const std::string& participant_name,
          const DdsIdentity& identity = {});
  ~DdsNode();
  DdsNode(const DdsNode&) = delete;
  DdsNode& operator=(const DdsNode&) = delete;

  eprosima::fastdds::dds::DataWriter* createWriter(const std::string& ros_topic, const std::string& type_name,
                                                   const TypeSupportMaker& type_support, QosPreset qos);
  eprosima::fastdds::dds::DataReader* createReader(const std::string& ros_topic, const std::string& type_name,
                                                   const TypeSupportMaker& type_support, QosPreset qos,
                                                   eprosima::fastdds::dds::DataReaderListener* listener);
  void deleteWriter(eprosima::fastdds::dds::DataWriter* writer);
  void deleteReader(eprosima::fastdds::dds::DataReader* reader);

  bool lockstep() const { return lockstep_; }

 private:
  eprosima::fastdds::dds::Topic* topic(const std::string& ros_topic, const std::string& type_name,
                                       const TypeSupportMaker& type_support);

  std::string permissionsHint() const;

  bool lockstep_;
  std::string permissions_;  // the permissions document under DDS Security, for messages
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::TypeSupport> types_;    // by ROS type name
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;         // by ROS topic name
  std::map<std::string, std::string> topic_types_;                       // ROS topic -> ROS type
};

}  // namespace uampc
