// ROS 2's conventions for names on the DDS wire (docs/dev/architecture.md section 4), in one place:
// the runtime uses them to create topics, the recorder, player and topic tools to read what others
// created.
#pragma once

#include <optional>
#include <string>

namespace uampc {

// "/motor/state" travels as "rt/motor/state".
std::string ddsTopicName(const std::string& ros_topic);
// "rt/motor/state" -> "/motor/state"; "" for a DDS topic that is not a ROS topic (no "rt/" prefix).
std::string rosTopicName(const std::string& dds_topic);

// "sensor_msgs/msg/PointCloud2" -> "sensor_msgs::msg::dds_::PointCloud2_" (what fastddsgen -typeros2
// and every ROS 2 rmw name the type on the wire).
std::string ddsTypeName(const std::string& ros_type);
// The inverse; "" for a DDS type name that does not follow the convention.
std::string rosTypeName(const std::string& dds_type);

// Fast DDS maps domains to UDP ports; 232 is the highest that fits the default port mapping.
constexpr int kMaxDomainId = 232;
// ROS_DOMAIN_ID, as a ROS 2 user expects it to be honoured where nothing else names the domain (a
// scene's domain_id, a command's --domain); nullopt when unset or empty. Throws
// std::invalid_argument when it is not a domain id.
std::optional<int> rosDomainIdFromEnvironment();

}  // namespace uampc
