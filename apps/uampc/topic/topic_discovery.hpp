// What DDS discovery tells about a domain: the participants and the writers and readers of every
// topic, of uampc and of any other vendor, from Fast DDS's participant listener (the built-in
// discovery topics of any DDS implementation carry them). The tool's own participant is left out.
#pragma once

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "uampc/runtime/dds_security.hpp"

namespace uampc::app {

struct DiscoveredParticipant {
  std::string name;         // as it names itself; uampc's processes use their process group's name
  std::string guid_prefix;  // "01.0f.3c.a1.d2.00.00.00.01.00.00.00"
  std::uint8_t vendor[2] = {0, 0};
};

struct DiscoveredEndpoint {
  std::string topic;        // DDS name: "rt/motor/state"
  std::string type;         // DDS type name: "sensor_msgs::msg::dds_::JointState_"
  std::string guid_prefix;  // of its participant
  bool reliable = false;
  bool transient_local = false;
};

// One topic: every writer and reader of it.
struct DiscoveredTopic {
  std::string dds_name;
  std::vector<DiscoveredEndpoint> writers;
  std::vector<DiscoveredEndpoint> readers;
};

// "01.0f (eProsima Fast DDS)"; the vendor's name only for the vendors known here.
std::string vendorText(const std::uint8_t vendor[2]);
// How uampc names a DDS topic to a user: its ROS name ("/motor/state") for a ROS topic, else its
// DDS name. The inverse, for a name a user typed: a name starting with '/' is a ROS topic.
std::string shownTopicName(const std::string& dds_topic);
std::string ddsTopicFromUser(const std::string& topic);
// A DDS type as a user knows it: its ROS name when it follows ROS's convention, else the DDS name.
std::string shownTypeName(const std::string& dds_type);

class TopicDiscovery {
 public:
  // Joins the domain with a participant named "uampc topic", authenticated with identity when it
  // is enabled (a secured domain, dds_security.hpp). Throws std::runtime_error if it cannot.
  explicit TopicDiscovery(int domain_id, const DdsIdentity& identity = {});
  ~TopicDiscovery();
  TopicDiscovery(const TopicDiscovery&) = delete;
  TopicDiscovery& operator=(const TopicDiscovery&) = delete;

  // What has been discovered so far, by DDS topic name.
  std::map<std::string, DiscoveredTopic> topics() const;
  std::map<std::string, DiscoveredParticipant> participants() const;  // by GUID prefix

  eprosima::fastdds::dds::DomainParticipant* participant() { return participant_; }

 private:
  class Listener : public eprosima::fastdds::dds::DomainParticipantListener {
   public:
    explicit Listener(TopicDiscovery& owner) : owner_(owner) {}
    void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                  eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
    void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
    void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                 eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;

   private:
    TopicDiscovery& owner_;
  };

  void update(std::map<std::string, DiscoveredEndpoint>& endpoints, const std::string& guid, bool removed,
              DiscoveredEndpoint endpoint);

  Listener listener_{*this};
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  std::string own_prefix_;
  mutable std::mutex mutex_;
  std::map<std::string, DiscoveredParticipant> participants_;
  std::map<std::string, DiscoveredEndpoint> writers_;  // by GUID
  std::map<std::string, DiscoveredEndpoint> readers_;
};

}  // namespace uampc::app
