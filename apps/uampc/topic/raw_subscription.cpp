#include "topic/raw_subscription.hpp"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <algorithm>
#include <stdexcept>

namespace uampc::app {

using namespace eprosima::fastdds::dds;

namespace {

bool allReliable(const DiscoveredTopic& topic) {
  return std::all_of(topic.writers.begin(), topic.writers.end(), [](const auto& w) { return w.reliable; });
}

DataReaderQos readerQos(Subscriber* subscriber, const DiscoveredTopic& topic, ReaderPolicy policy) {
  const bool writers_reliable = allReliable(topic);
  const bool transient_local = isLatched(topic);
  const bool reliable = policy == ReaderPolicy::kLikeTheWriters ? writers_reliable : transient_local;
  DataReaderQos qos = subscriber->get_default_datareader_qos();
  qos.reliability().kind = reliable ? RELIABLE_RELIABILITY_QOS : BEST_EFFORT_RELIABILITY_QOS;
  qos.durability().kind = transient_local ? TRANSIENT_LOCAL_DURABILITY_QOS : VOLATILE_DURABILITY_QOS;
  qos.history().kind = KEEP_LAST_HISTORY_QOS;
  // Enough for bursts, bounded for large samples.
  qos.history().depth = RawSubscription::kHistoryDepth;
  // Samples larger than the type's hint are reallocated rather than refused.
  qos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  return qos;
}

}  // namespace

bool isLatched(const DiscoveredTopic& topic) {
  return allReliable(topic) &&
         std::all_of(topic.writers.begin(), topic.writers.end(), [](const auto& w) { return w.transient_local; });
}

RawSubscription::RawSubscription(DomainParticipant* participant, const DiscoveredTopic& topic, OnSample on_sample,
                                 ReaderPolicy policy)
    : participant_(participant), listener_(std::move(on_sample)) {
  const std::string& type = topic.writers.at(0).type;
  TypeSupport support(SerializedTypeSupport::forDdsType(type));
  if (support.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("cannot register DDS type " + type);
  }
  topic_ = participant_->create_topic(topic.dds_name, type, TOPIC_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  if (!topic_ || !subscriber_) throw std::runtime_error("cannot create DDS topic " + topic.dds_name);
  reader_ =
      subscriber_->create_datareader(topic_, readerQos(subscriber_, topic, policy), &listener_, StatusMask::data_available());
  if (!reader_) throw std::runtime_error("cannot create a DDS reader on " + topic.dds_name);
}

RawSubscription::~RawSubscription() {
  // The reader goes first, so that no callback runs into a listener being destroyed.
  if (reader_) subscriber_->delete_datareader(reader_);
  if (subscriber_) participant_->delete_subscriber(subscriber_);
  if (topic_) participant_->delete_topic(topic_);
}

void RawSubscription::Listener::on_data_available(DataReader* reader) {
  SerializedMessage sample;
  SampleInfo info;
  while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
    if (info.valid_data) {
      const auto nanoseconds = [](const eprosima::fastrtps::rtps::Time_t& t) {
        return Time{static_cast<std::int64_t>(t.seconds()) * 1000000000 + t.nanosec()};
      };
      on_sample_(std::move(sample), {std::chrono::steady_clock::now(), nanoseconds(info.reception_timestamp),
                                     nanoseconds(info.source_timestamp)});
    }
    sample = SerializedMessage();
  }
}

}  // namespace uampc::app
