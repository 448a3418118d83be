#include "uampc/recording/recorded_topic.hpp"

#include <string>

#include "uampc/runtime/dds_node.hpp"

namespace uampc::recording {

namespace {

constexpr char kQosKey[] = "uampc_qos";
constexpr char kClockKey[] = "uampc_clock";
constexpr char kRosbagQosKey[] = "offered_qos_profiles";

// rosbag2's (Humble) YAML for one offered QoS profile, of the QoS the runtime gives the preset
// (dds_node.hpp): enums as rmw numbers (history 1 keep last, 2 keep all; reliability 1 reliable,
// 2 best effort; durability 1 transient local, 2 volatile; liveliness 1 automatic), durations
// "infinite" as rosbag2 writes them.
std::string rosbagQosProfile(QosPreset preset, RecordingClock clock) {
  using namespace eprosima::fastdds::dds;
  const DataWriterQos qos = writerQosOf(preset, clock == RecordingClock::kLockstep);
  const int history = qos.history().kind == KEEP_ALL_HISTORY_QOS ? 2 : 1;
  const int reliability = qos.reliability().kind == RELIABLE_RELIABILITY_QOS ? 1 : 2;
  const int durability = qos.durability().kind == TRANSIENT_LOCAL_DURABILITY_QOS ? 1 : 2;
  const std::string infinite = "{sec: 2147483647, nsec: 4294967295}";
  return "- history: " + std::to_string(history) + "\n  depth: " + std::to_string(qos.history().depth) +
         "\n  reliability: " + std::to_string(reliability) + "\n  durability: " + std::to_string(durability) +
         "\n  deadline: " + infinite + "\n  lifespan: " + infinite +
         "\n  liveliness: 1\n  liveliness_lease_duration: " + infinite + "\n  avoid_ros_namespace_conventions: false";
}

}  // namespace

std::map<std::string, std::string> channelMetadata(const RecordedTopic& topic, RecordingClock clock) {
  return {{kRosbagQosKey, rosbagQosProfile(topic.qos, clock)},
          {kQosKey, toString(topic.qos)},
          {kClockKey, clock == RecordingClock::kLockstep ? "lockstep" : "realtime"}};
}

std::optional<QosPreset> qosFromMetadata(const std::map<std::string, std::string>& metadata) {
  const auto it = metadata.find(kQosKey);
  if (it == metadata.end()) return std::nullopt;
  for (QosPreset preset : {QosPreset::kSensor, QosPreset::kControl, QosPreset::kLatched}) {
    if (it->second == toString(preset)) return preset;
  }
  return std::nullopt;
}

std::optional<RecordingClock> clockFromMetadata(const std::map<std::string, std::string>& metadata) {
  const auto it = metadata.find(kClockKey);
  if (it == metadata.end()) return std::nullopt;
  if (it->second == "lockstep") return RecordingClock::kLockstep;
  if (it->second == "realtime") return RecordingClock::kRealtime;
  return std::nullopt;
}

}  // namespace uampc::recording
