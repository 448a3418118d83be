#include "view/topic_bridge.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <set>

#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/message_type.hpp"

namespace uampc::app {

namespace {

constexpr const char* kClockTopic = "rt/clock";

std::uint64_t wallClockNanoseconds() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

std::int64_t clockNanoseconds(const SerializedMessage& sample) {
  // Encapsulation header (2 bytes of kind, 2 of options), then builtin_interfaces/Time: int32 sec,
  // uint32 nanosec, in the byte order the kind names (odd: little endian).
  const auto& d = sample.data;
  if (d.size() < 12 || d[0] != 0) return -1;
  const bool little = (d[1] & 1) != 0;
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(d[at + (little ? i : 3 - i)]) << (8 * i);
    return v;
  };
  const auto sec = static_cast<std::int32_t>(u32(4));
  const std::uint32_t nanosec = u32(8);
  if (sec < 0 || nanosec >= 1000000000u) return -1;
  return std::int64_t(sec) * 1000000000 + nanosec;
}

TopicBridge::TopicBridge(TopicDiscovery& discovery, foxglove::Server& server)
    : discovery_(discovery), server_(server) {}

TopicBridge::~TopicBridge() {
  // Readers first: their callbacks publish into the server.
  readers_.clear();
  clock_reader_.reset();
}

void TopicBridge::update() {
  const auto topics = discovery_.topics();
  withdrawGoneTopics(topics);
  advertiseNewTopics(topics);
  readSubscribedTopics(topics);
  followClock(topics);
}

std::string TopicBridge::schemaOf(const std::string& ros_type) {
  std::string schema;
  try {
    schema = messageDefinition(ros_type);
    if (schema.empty() && !catalog_) {
      // A type from a user's message library: loading the component libraries registers it,
      // as launching a scene with them would.
      catalog_ = std::make_unique<ComponentCatalog>();
      catalog_->all();
      schema = messageDefinition(ros_type);
    }
  } catch (const std::runtime_error& e) {
    std::cerr << "uampc view: the definition of " << ros_type << " cannot be derived: " << e.what() << "\n";
  }
  return schema;
}

void TopicBridge::advertiseNewTopics(const std::map<std::string, DiscoveredTopic>& topics) {
  for (const auto& [dds_name, topic] : topics) {
    if (topic.writers.empty() || advertised_.count(dds_name) || skipped_.count(dds_name)) continue;
    const std::string name = rosTopicName(dds_name);
    if (name.empty()) continue;  // DDS's own or a vendor's internal topic
    const std::string& dds_type = topic.writers.front().type;
    const std::string type = rosTypeName(dds_type);
    const std::string schema = type.empty() ? std::string() : schemaOf(type);
    if (schema.empty()) {
      std::cerr << "uampc view: " << name << " is not offered: its type " << dds_type
                << " has no message definition here (not known to uampc or its component libraries, or its IDL "
                   "could not be read), so no client could decode it\n";
      skipped_[dds_name] = true;
      continue;
    }
    const foxglove::ChannelId id = server_.advertise({0, name, "cdr", type, schema, "ros2msg"});
    advertised_[dds_name] = {id, dds_type};
    ++offered_;
  }
}

void TopicBridge::withdrawGoneTopics(const std::map<std::string, DiscoveredTopic>& topics) {
  for (auto it = advertised_.begin(); it != advertised_.end();) {
    const auto topic = topics.find(it->first);
    const bool gone =
        topic == topics.end() || topic->second.writers.empty() || topic->second.writers.front().type != it->second.type;
    if (!gone) {
      ++it;
      continue;
    }
    readers_.erase(it->second.id);
    server_.unadvertise(it->second.id);  // and what it kept of the topic
    it = advertised_.erase(it);
  }
}

void TopicBridge::readSubscribedTopics(const std::map<std::string, DiscoveredTopic>& topics) {
  const std::set<foxglove::ChannelId> wanted = server_.subscribedChannels();
  for (auto it = readers_.begin(); it != readers_.end();) {
    if (wanted.count(it->first)) {
      ++it;
      continue;
    }
    const foxglove::ChannelId id = it->first;
    it = readers_.erase(it);
    // After the reader: none of its samples can come in after this. The next reader brings the
    // kept samples of a latched topic anew.
    server_.forgetLatched(id);
  }
  const auto clock = advertised_.find(kClockTopic);
  clock_channel_ = clock != advertised_.end() && wanted.count(clock->second.id) ? std::int64_t(clock->second.id) : -1;
  for (const auto& [dds_name, advertised] : advertised_) {
    // /clock has its reader for good (followClock), which also forwards it.
    if (!wanted.count(advertised.id) || readers_.count(advertised.id) || dds_name == kClockTopic) continue;
    const foxglove::ChannelId id = advertised.id;
    const DiscoveredTopic& topic = topics.at(dds_name);
    // A latched topic's kept samples reach this reader once: the server keeps them for the
    // clients that subscribe later (docs/decisions/viewer-latched-topics.md).
    const std::size_t keep = isLatched(topic) ? RawSubscription::kHistoryDepth : 0;
    try {
      readers_[id] = std::make_unique<RawSubscription>(
          discovery_.participant(), topic,
          [this, id, keep](SerializedMessage&& sample, const SampleTimes& times) {
            const auto time_ns = static_cast<std::uint64_t>(std::max<std::int64_t>(0, times.published.ns));
            // The sample's own bytes, moved, not copied: every subscription shares them.
            auto payload = std::make_shared<const std::vector<std::uint8_t>>(std::move(sample.data));
            if (keep > 0) {
              server_.publishLatched(id, time_ns, std::move(payload), keep);
            } else {
              server_.publish(id, time_ns, std::move(payload));
            }
          },
          ReaderPolicy::kNeverHoldWriters);
    } catch (const std::runtime_error& e) {
      // Said once: the channel stays advertised, and its subscribers get nothing.
      readers_[id] = nullptr;
      std::cerr << "uampc view: cannot read " << rosTopicName(dds_name) << ": " << e.what() << "\n";
    }
  }
}

void TopicBridge::followClock(const std::map<std::string, DiscoveredTopic>& topics) {
  const auto clock = topics.find(kClockTopic);
  if (!clock_reader_ && !clock_unreadable_ && clock != topics.end() && !clock->second.writers.empty()) {
    try {
      clock_reader_ = std::make_unique<RawSubscription>(
          discovery_.participant(), clock->second,
          [this](SerializedMessage&& sample, const SampleTimes&) {
            const std::int64_t t = clockNanoseconds(sample);
            if (t < 0) return;
            latest_clock_ns_ = t;
            // Stamped with the time it tells: the clock's writer stamps its samples with the wall clock.
            const std::int64_t channel = clock_channel_;
            if (channel >= 0) {
              server_.publish(static_cast<foxglove::ChannelId>(channel), static_cast<std::uint64_t>(t),
                              std::make_shared<const std::vector<std::uint8_t>>(std::move(sample.data)));
            }
          },
          ReaderPolicy::kNeverHoldWriters);
    } catch (const std::runtime_error& e) {
      clock_unreadable_ = true;  // said once; the clients follow the wall clock
      std::cerr << "uampc view: cannot read /clock: " << e.what() << "\n";
    }
  }
  const std::int64_t now = latest_clock_ns_;
  if (now < 0) {
    // No simulated clock (a rig, or nothing yet): the clients follow the wall clock, which is what
    // real-time writers stamp their samples with.
    server_.broadcastTime(wallClockNanoseconds());
  } else if (now != sent_clock_ns_) {
    server_.broadcastTime(static_cast<std::uint64_t>(now));
    sent_clock_ns_ = now;
  }
}

}  // namespace uampc::app
