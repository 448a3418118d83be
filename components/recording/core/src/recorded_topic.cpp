#include "uampc/recording/recorded_topic.hpp"

#include <string>

namespace uampc::recording {

namespace {

constexpr char kQosKey[] = "uampc_qos";
constexpr char kClockKey[] = "uampc_clock";
constexpr char kRosbagQosKey[] = "offered_qos_profiles";

// rosbag2's (Humble) YAML for one offered QoS profile, enums as rmw numbers: history 1 keep last,
// 2 keep all; reliability 1 reliable, 2 best effort; durability 1 transient local, 2 volatile;
// liveliness 1 automatic; durations "infinite" as rosbag2 writes them.
std::string rosbagQosProfile(QosPreset qos, RecordingClock clock) {
  const bool lockstep = clock == RecordingClock::kLockstep;
  int history = 1, depth = 10, reliability = 1, durability = 2;
  switch (qos) {
    case QosPreset::kSensor:
      depth = 5;
      reliability = lockstep ? 1 : 2;
      history = lockstep ? 2 : 1;
      break;
    case QosPreset::kControl:
      history = lockstep ? 2 : 1;
      break;
    case QosPreset::kLatched:
      depth = 100;
      durability = 1;
      break;
  }
  const std::string infinite = "{sec: 2147483647, nsec: 4294967295}";
  return "- history: " + std::to_string(history) + "\n  depth: " + std::to_string(depth) +
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
