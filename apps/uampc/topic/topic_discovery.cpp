#include "topic/topic_discovery.hpp"

#include <fastdds/rtps/builtin/data/ParticipantProxyData.h>
#include <fastdds/rtps/builtin/data/ReaderProxyData.h>
#include <fastdds/rtps/builtin/data/WriterProxyData.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "uampc/runtime/dds_names.hpp"

namespace uampc::app {

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::GuidPrefix_t;
using eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
using eprosima::fastrtps::rtps::ReaderDiscoveryInfo;
using eprosima::fastrtps::rtps::WriterDiscoveryInfo;

namespace {

std::string prefixText(const GuidPrefix_t& prefix) {
  std::ostringstream text;
  text << prefix;
  return text.str();
}

template <typename Guid>
std::string guidText(const Guid& guid) {
  std::ostringstream text;
  text << guid;
  return text.str();
}

// A writer or reader as its proxy data (WriterProxyData, ReaderProxyData) describes it.
template <typename ProxyData>
DiscoveredEndpoint endpointOf(const ProxyData& data) {
  DiscoveredEndpoint e;
  e.topic = data.topicName().to_string();
  e.type = data.typeName().to_string();
  e.guid_prefix = prefixText(data.guid().guidPrefix);
  e.reliable = data.m_qos.m_reliability.kind == RELIABLE_RELIABILITY_QOS;
  e.transient_local = data.m_qos.m_durability.kind != VOLATILE_DURABILITY_QOS;
  return e;
}

}  // namespace

std::string vendorText(const std::uint8_t vendor[2]) {
  // The vendor ids the OMG assigned (DDSI-RTPS 2.5, 8.3.3.1.3) of the implementations a robot may run.
  struct Vendor {
    std::uint8_t id;
    const char* name;
  };
  static const Vendor kVendors[] = {{0x01, "RTI Connext DDS"},
                                    {0x02, "OpenSplice DDS"},
                                    {0x03, "OpenDDS"},
                                    {0x06, "CoreDX DDS"},
                                    {0x0a, "RTI Connext DDS Micro"},
                                    {0x0f, "eProsima Fast DDS"},
                                    {0x10, "Eclipse Cyclone DDS"},
                                    {0x11, "GurumDDS"},
                                    {0x12, "RustDDS"},
                                    {0x14, "Dust DDS"}};
  char text[16];
  std::snprintf(text, sizeof text, "%02x.%02x", vendor[0], vendor[1]);
  std::string result = text;
  if (vendor[0] != 0x01) return result;
  for (const Vendor& v : kVendors) {
    if (v.id == vendor[1]) return result + " (" + v.name + ")";
  }
  return result;
}

std::string shownTopicName(const std::string& dds_topic) {
  const std::string ros_name = rosTopicName(dds_topic);
  return ros_name.empty() ? dds_topic : ros_name;
}

std::string ddsTopicFromUser(const std::string& topic) {
  return !topic.empty() && topic.front() == '/' ? ddsTopicName(topic) : topic;
}

std::string shownTypeName(const std::string& dds_type) {
  const std::string ros_name = rosTypeName(dds_type);
  return ros_name.empty() ? dds_type : ros_name;
}

TopicDiscovery::TopicDiscovery(int domain_id, const DdsIdentity& identity) {
  auto* factory = DomainParticipantFactory::get_instance();
  DomainParticipantQos qos = factory->get_default_participant_qos();
  qos.name("uampc topic");
  applyDdsSecurity(qos, identity);
  participant_ = factory->create_participant(domain_id, qos, &listener_, StatusMask::none());
  if (!participant_) {
    throw std::runtime_error("cannot create a DDS participant on domain " + std::to_string(domain_id) +
                             (identity.enabled() ? " with DDS Security identity " + identity.certificate : ""));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  own_prefix_ = prefixText(participant_->guid().guidPrefix);
}

TopicDiscovery::~TopicDiscovery() {
  participant_->set_listener(nullptr);
  participant_->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

std::map<std::string, DiscoveredTopic> TopicDiscovery::topics() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::map<std::string, DiscoveredTopic> topics;
  for (const auto& [guid, writer] : writers_) {
    topics[writer.topic].dds_name = writer.topic;
    topics[writer.topic].writers.push_back(writer);
  }
  for (const auto& [guid, reader] : readers_) {
    topics[reader.topic].dds_name = reader.topic;
    topics[reader.topic].readers.push_back(reader);
  }
  return topics;
}

std::map<std::string, DiscoveredParticipant> TopicDiscovery::participants() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return participants_;
}

void TopicDiscovery::update(std::map<std::string, DiscoveredEndpoint>& endpoints, const std::string& guid, bool removed,
                            DiscoveredEndpoint endpoint) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (endpoint.guid_prefix == own_prefix_) return;
  if (removed) {
    endpoints.erase(guid);
  } else {
    endpoints[guid] = std::move(endpoint);
  }
}

void TopicDiscovery::Listener::on_participant_discovery(DomainParticipant*, ParticipantDiscoveryInfo&& info) {
  const std::string prefix = prefixText(info.info.m_guid.guidPrefix);
  std::lock_guard<std::mutex> lock(owner_.mutex_);
  if (info.status == ParticipantDiscoveryInfo::REMOVED_PARTICIPANT ||
      info.status == ParticipantDiscoveryInfo::DROPPED_PARTICIPANT) {
    // Its endpoints go with it, whether or not their removal is reported one by one.
    owner_.participants_.erase(prefix);
    for (auto* endpoints : {&owner_.writers_, &owner_.readers_}) {
      for (auto it = endpoints->begin(); it != endpoints->end();) {
        it = it->second.guid_prefix == prefix ? endpoints->erase(it) : std::next(it);
      }
    }
    return;
  }
  DiscoveredParticipant& p = owner_.participants_[prefix];
  p.name = info.info.m_participantName.to_string();
  p.guid_prefix = prefix;
  p.vendor[0] = info.info.m_VendorId[0];
  p.vendor[1] = info.info.m_VendorId[1];
}

void TopicDiscovery::Listener::on_publisher_discovery(DomainParticipant*, WriterDiscoveryInfo&& info) {
  owner_.update(owner_.writers_, guidText(info.info.guid()), info.status == WriterDiscoveryInfo::REMOVED_WRITER,
                endpointOf(info.info));
}

void TopicDiscovery::Listener::on_subscriber_discovery(DomainParticipant*, ReaderDiscoveryInfo&& info) {
  owner_.update(owner_.readers_, guidText(info.info.guid()), info.status == ReaderDiscoveryInfo::REMOVED_READER,
                endpointOf(info.info));
}

}  // namespace uampc::app
