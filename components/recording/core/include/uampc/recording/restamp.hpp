// Moves recorded samples in time: `uampc play --restamp` plays a recording as if it were happening
// now, for a real-time system that pairs the played samples with live ones by their stamps (the LO
// pairs each scan with the encoder states of its motor, docs/user/rig.md).
#pragma once

#include <map>
#include <string>

#include "uampc/runtime/serialized_message.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc::recording {

class Restamper {
 public:
  explicit Restamper(Time offset) : offset_(offset) {}
  void setOffset(Time offset) { offset_ = offset; }
  Time offset() const { return offset_; }

  // Adds the offset to the header stamp of a sample whose type starts with a std_msgs/Header (its
  // first field, as in every stamped ROS message), and to the absolute point times of a
  // PointCloud2 that has them (livox_ros_driver2's layout). Samples without a header are left as
  // they are; false then. Throws std::runtime_error for a sample too short for its header.
  // Decision: a topic's point layout does not change (drivers publish one), so whether its clouds
  // have absolute times is decoded once per topic; the others are never decoded.
  bool restamp(const std::string& topic, const std::string& ros_type, SerializedMessage& sample);

 private:
  bool startsWithHeader(const std::string& ros_type);
  bool hasAbsolutePointTimes(const std::string& topic, const SerializedMessage& cloud);

  Time offset_;
  std::map<std::string, bool> starts_with_header_;       // by ROS type name
  std::map<std::string, bool> absolute_point_times_;     // by topic, for PointCloud2 topics
};

}  // namespace uampc::recording
