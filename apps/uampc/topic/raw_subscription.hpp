// A reader of one topic that keeps its samples as CDR bytes (SerializedTypeSupport), registered
// under the DDS type name its writers use, so it reads any type, known to uampc or not.
#pragma once

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <chrono>
#include <cstdint>
#include <functional>

#include "topic/topic_discovery.hpp"
#include "uampc/runtime/serialized_message.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc::app {

// When a sample was published and when it arrived.
struct SampleTimes {
  std::chrono::steady_clock::time_point arrived;  // for rates
  Time received;                                  // wall clock at reception (Fast DDS's reception timestamp)
  Time published;  // its writer's source timestamp (sim time for a lockstep scene's writers)
};

// How a raw reader matches its writers.
enum class ReaderPolicy {
  kLikeTheWriters,  // reliable when every writer is, so that nothing is lost (record, topic echo)
  // Best effort except for latched topics: a reliable writer never waits for this reader, so a
  // slow one cannot hold up a run (the live viewer, docs/decisions/live-viewer.md). Latched topics
  // stay reliable and transient-local, which is how their kept samples reach a late reader.
  kNeverHoldWriters,
};

// Whether `topic` is latched: every writer reliable and transient-local, so that a reader that
// asks for it gets the samples they keep when it matches (ROS 2's /tf_static, uampc's maps).
bool isLatched(const DiscoveredTopic& topic);

class RawSubscription {
 public:
  // Samples a reader keeps not yet taken; also how many kept samples of a latched topic it takes.
  static constexpr std::int32_t kHistoryDepth = 100;

  // Called on Fast DDS's thread for every sample.
  using OnSample = std::function<void(SerializedMessage&& sample, const SampleTimes& times)>;

  // Reads `topic` as its first writer's type. QoS as discovered: reliable when every writer is
  // (a reliable reader would not match a best-effort writer), transient-local when every writer is,
  // so that a latched topic's kept samples arrive too; kNeverHoldWriters relaxes the first.
  // Throws std::runtime_error when DDS refuses the reader.
  RawSubscription(eprosima::fastdds::dds::DomainParticipant* participant, const DiscoveredTopic& topic,
                  OnSample on_sample, ReaderPolicy policy = ReaderPolicy::kLikeTheWriters);
  ~RawSubscription();
  RawSubscription(const RawSubscription&) = delete;
  RawSubscription& operator=(const RawSubscription&) = delete;

 private:
  class Listener : public eprosima::fastdds::dds::DataReaderListener {
   public:
    explicit Listener(OnSample on_sample) : on_sample_(std::move(on_sample)) {}
    void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;

   private:
    OnSample on_sample_;
  };

  eprosima::fastdds::dds::DomainParticipant* participant_;
  Listener listener_;
  eprosima::fastdds::dds::Topic* topic_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};

}  // namespace uampc::app
