// Everything a DDS domain publishes, offered to Foxglove clients: each discovered ROS topic becomes
// a channel of the server, with the ros2msg schema uampc derives from the type's IDL (as for MCAP
// recordings), and only the channels some client subscribes to are read from DDS. Samples are
// forwarded as the CDR bytes that arrived, stamped with their writer's source time (sim time in a
// lockstep run). The domain's /clock, when there is one, sets the clients' time.
// docs/user/viewing.md for users, docs/decisions/live-viewer.md for why.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <string>

#include "topic/raw_subscription.hpp"
#include "topic/topic_discovery.hpp"
#include "uampc/foxglove/server.hpp"
#include "uampc/runtime/component_library.hpp"

namespace uampc::app {

class TopicBridge {
 public:
  TopicBridge(TopicDiscovery& discovery, foxglove::Server& server);
  ~TopicBridge();
  TopicBridge(const TopicBridge&) = delete;
  TopicBridge& operator=(const TopicBridge&) = delete;

  // Advertises new topics, withdraws those whose writers left, reads what clients subscribe to
  // and sends the latest clock. Called periodically from one thread.
  void update();

  std::size_t channelsOffered() const { return offered_; }  // since the start, withdrawn ones too

 private:
  struct Advertised {
    foxglove::ChannelId id;
    std::string type;  // DDS type name: a topic whose type changes is advertised again
  };

  void advertiseNewTopics(const std::map<std::string, DiscoveredTopic>& topics);
  void withdrawGoneTopics(const std::map<std::string, DiscoveredTopic>& topics);
  void readSubscribedTopics(const std::map<std::string, DiscoveredTopic>& topics);
  void followClock(const std::map<std::string, DiscoveredTopic>& topics);
  std::string schemaOf(const std::string& ros_type);

  TopicDiscovery& discovery_;
  foxglove::Server& server_;
  std::map<std::string, Advertised> advertised_;  // by DDS topic name
  std::size_t offered_ = 0;
  std::map<foxglove::ChannelId, std::unique_ptr<RawSubscription>> readers_;
  std::map<std::string, bool> skipped_;  // topics said to be unviewable, said once
  std::unique_ptr<RawSubscription> clock_reader_;
  bool clock_unreadable_ = false;
  std::atomic<std::int64_t> latest_clock_ns_{-1};
  std::atomic<std::int64_t> clock_channel_{-1};  // /clock's channel while a client subscribes to it
  std::int64_t sent_clock_ns_ = -1;
  std::unique_ptr<ComponentCatalog> catalog_;  // users' libraries, loaded for their types' IDL
};

// The time a /clock sample carries (rosgraph_msgs/Clock as CDR), or -1 when it is not one.
std::int64_t clockNanoseconds(const SerializedMessage& sample);

}  // namespace uampc::app
