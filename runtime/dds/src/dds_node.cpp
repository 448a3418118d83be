#include "uampc/runtime/dds_node.hpp"

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <stdexcept>

namespace uampc {

using namespace eprosima::fastdds::dds;

namespace {

// The QoS a preset means; in lockstep mode the loop must not lose a sample, so everything is
// reliable and keeps all samples until they are acknowledged (bounded by the lockstep protocol,
// which waits for acknowledgement every step).
template <typename Qos>
void applyPreset(Qos& qos, QosPreset preset, bool lockstep) {
  switch (preset) {
    case QosPreset::kSensor:
      qos.reliability().kind = lockstep ? RELIABLE_RELIABILITY_QOS : BEST_EFFORT_RELIABILITY_QOS;
      qos.durability().kind = VOLATILE_DURABILITY_QOS;
      qos.history().kind = lockstep ? KEEP_ALL_HISTORY_QOS : KEEP_LAST_HISTORY_QOS;
      qos.history().depth = 5;
      break;
    case QosPreset::kControl:
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = VOLATILE_DURABILITY_QOS;
      qos.history().kind = lockstep ? KEEP_ALL_HISTORY_QOS : KEEP_LAST_HISTORY_QOS;
      qos.history().depth = 10;
      break;
    case QosPreset::kLatched:
      qos.reliability().kind = RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = TRANSIENT_LOCAL_DURABILITY_QOS;
      // Late joiners get the last kLatchedHistoryDepth samples: a world is sent in no more chunks.
      qos.history().kind = KEEP_LAST_HISTORY_QOS;
      qos.history().depth = kLatchedHistoryDepth;
      break;
  }
}

// The participant QoS of the profile file's default participant profile (is_default_profile="true"),
// or Fast DDS's defaults without a file. Fast DDS 2.9 computes its default participant QoS once,
// when the factory first loads its own default profiles; a file loaded later only changes it after
// set_default_participant_qos(PARTICIPANT_QOS_DEFAULT), which re-reads the XML defaults. Without that
// the file's transports, segment sizes and security properties were silently ignored.
DomainParticipantQos participantQosFrom(const std::string& profile_file) {
  auto* factory = DomainParticipantFactory::get_instance();
  factory->load_profiles();
  if (!profile_file.empty()) {
    if (factory->load_XML_profiles_file(profile_file) != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error(profile_file + ": Fast DDS could not load this XML profile file");
    }
    factory->set_default_participant_qos(PARTICIPANT_QOS_DEFAULT);
  }
  return factory->get_default_participant_qos();
}

}  // namespace

DataWriterQos writerQosOf(QosPreset preset, bool lockstep) {
  DataWriterQos qos = DATAWRITER_QOS_DEFAULT;
  applyPreset(qos, preset, lockstep);
  return qos;
}

DdsNode::DdsNode(int domain_id, const std::string& profile_file, bool lockstep, const std::string& participant_name,
                 const DdsIdentity& identity)
    : lockstep_(lockstep), permissions_(identity.permissions) {
  auto* factory = DomainParticipantFactory::get_instance();
  DomainParticipantQos qos = participantQosFrom(profile_file);
  qos.name(participant_name);
  applyDdsSecurity(qos, identity);
  participant_ = factory->create_participant(domain_id, qos);
  if (!participant_) {
    throw std::runtime_error("cannot create a DDS participant on domain " + std::to_string(domain_id) +
                             (profile_file.empty() ? std::string()
                                                   : " with the profile " + profile_file +
                                                         " (its transports or security files; Fast DDS's log above "
                                                         "says which)"));
  }
  publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  if (!publisher_ || !subscriber_) throw std::runtime_error("cannot create a DDS publisher or subscriber");
}

DdsNode::~DdsNode() {
  if (!participant_) return;
  participant_->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

Topic* DdsNode::topic(const std::string& ros_topic, const std::string& type_name,
                      const TypeSupportMaker& type_support) {
  if (auto it = topics_.find(ros_topic); it != topics_.end()) {
    if (topic_types_[ros_topic] != type_name) {
      throw std::runtime_error("topic " + ros_topic + " is used with two types: " + topic_types_[ros_topic] + " and " +
                               type_name);
    }
    return it->second;
  }
  auto type = types_.find(type_name);
  if (type == types_.end()) {
    TypeSupport support(type_support());
    if (support.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("cannot register DDS type " + type_name);
    }
    type = types_.emplace(type_name, support).first;
  }
  Topic* t = participant_->create_topic(ddsTopicName(ros_topic), type->second.get_type_name(), TOPIC_QOS_DEFAULT);
  if (!t) throw std::runtime_error("cannot create DDS topic " + ddsTopicName(ros_topic));
  topics_[ros_topic] = t;
  topic_types_[ros_topic] = type_name;
  return t;
}

DataWriter* DdsNode::createWriter(const std::string& ros_topic, const std::string& type_name,
                                  const TypeSupportMaker& type_support, QosPreset preset) {
  Topic* t = topic(ros_topic, type_name, type_support);
  DataWriterQos qos = publisher_->get_default_datawriter_qos();
  applyPreset(qos, preset, lockstep_);
  // Large samples (point clouds of 1 MB) are sent from the writing thread; asynchronous mode
  // would need a flow controller to fragment them.
  qos.publish_mode().kind = SYNCHRONOUS_PUBLISH_MODE;
  if (lockstep_) {
    // Lockstep never waits for acknowledgements (readers count samples instead), so heartbeats
    // only serve to free acknowledged samples from the keep-all history; 100 ms keeps it short.
    qos.reliable_writer_qos().times.heartbeatPeriod = eprosima::fastrtps::Duration_t(0, 100000000);
  }
  DataWriter* writer = publisher_->create_datawriter(t, qos);
  if (!writer) throw std::runtime_error("cannot create a DDS writer on " + ros_topic + permissionsHint());
  return writer;
}

DataReader* DdsNode::createReader(const std::string& ros_topic, const std::string& type_name,
                                  const TypeSupportMaker& type_support, QosPreset preset,
                                  DataReaderListener* listener) {
  Topic* t = topic(ros_topic, type_name, type_support);
  DataReaderQos qos = subscriber_->get_default_datareader_qos();
  applyPreset(qos, preset, lockstep_);
  DataReader* reader = subscriber_->create_datareader(t, qos, listener, StatusMask::data_available());
  if (!reader) throw std::runtime_error("cannot create a DDS reader on " + ros_topic + permissionsHint());
  return reader;
}

// Under DDS Security, Fast DDS refuses a writer or reader the permissions do not grant, and says
// nothing more.
std::string DdsNode::permissionsHint() const {
  if (permissions_.empty()) return {};
  return " (DDS Security: not permitted by " + permissions_ +
         "? `uampc security init` grants each process the topics the scene gives it)";
}

void DdsNode::deleteWriter(DataWriter* writer) { publisher_->delete_datawriter(writer); }
void DdsNode::deleteReader(DataReader* reader) { subscriber_->delete_datareader(reader); }

}  // namespace uampc
