// What a recording says about each of its topics besides the samples, and how it says it in an
// MCAP channel's metadata (docs/user/topics-and-recordings.md, "Recordings (MCAP)").
#pragma once

#include <map>
#include <optional>
#include <string>

#include "uampc/runtime/qos.hpp"

namespace uampc::recording {

struct RecordedTopic {
  std::string topic;  // ROS name, "/lidar/points"
  std::string type;   // ROS name, "sensor_msgs/msg/PointCloud2"
  QosPreset qos = QosPreset::kControl;
};

// Which clock stamped a recording: lockstep (sim time, one step per hop: a player in a lockstep
// scene reproduces the original steps) or real time (wall clock).
enum class RecordingClock { kLockstep, kRealtime };

// Channel metadata: rosbag2's "offered_qos_profiles" (so that `ros2 bag play` offers the same QoS)
// and uampc's own keys for the preset and the clock.
std::map<std::string, std::string> channelMetadata(const RecordedTopic& topic, RecordingClock clock);
// The preset and clock written by channelMetadata; nullopt for what a recording from another tool
// does not say.
std::optional<QosPreset> qosFromMetadata(const std::map<std::string, std::string>& metadata);
std::optional<RecordingClock> clockFromMetadata(const std::map<std::string, std::string>& metadata);

}  // namespace uampc::recording
