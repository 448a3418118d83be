#include "uampc/recording/restamp.hpp"

#include <cstring>
#include <sstream>
#include <stdexcept>

#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/message_type.hpp"
#include "uampc/runtime/typed_sample.hpp"

namespace uampc::recording {
namespace {

constexpr std::size_t kEncapsulation = 4;  // CDR's representation header
constexpr std::int64_t kNsPerSecond = 1'000'000'000;

sensor_msgs::msg::PointCloud2 decodeCloud(const SerializedMessage& sample) {
  sensor_msgs::msg::PointCloud2 cloud;
  if (!decodeSample(sample, cloud)) throw std::runtime_error("a PointCloud2 sample that does not decode");
  return cloud;
}

// A PointCloud2 with absolute point times: shifted through the real type, as its data says.
void shiftPointTimes(SerializedMessage& sample, Time offset) {
  sensor_msgs::msg::PointCloud2 cloud = decodeCloud(sample);
  pointcloud::shiftAbsoluteTimes(cloud, offset.seconds());
  sample = encodeSample(cloud);
}

}  // namespace

bool Restamper::startsWithHeader(const std::string& ros_type) {
  auto cached = starts_with_header_.find(ros_type);
  if (cached != starts_with_header_.end()) return cached->second;
  // The .msg text's first field line: "std_msgs/Header header".
  std::istringstream definition(messageDefinition(ros_type));
  bool header = false;
  for (std::string line; std::getline(definition, line);) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    header = line.compare(start, 16, "std_msgs/Header ") == 0;
    break;
  }
  return starts_with_header_[ros_type] = header;
}

bool Restamper::hasAbsolutePointTimes(const std::string& topic, const SerializedMessage& cloud) {
  auto cached = absolute_point_times_.find(topic);
  if (cached != absolute_point_times_.end()) return cached->second;
  return absolute_point_times_[topic] = pointcloud::hasAbsoluteTimes(decodeCloud(cloud));
}

bool Restamper::restamp(const std::string& topic, const std::string& ros_type, SerializedMessage& sample) {
  if (!startsWithHeader(ros_type)) return false;
  if (sample.data.size() < kEncapsulation + 8 || !(sample.data[1] & 1))
    throw std::runtime_error("a " + ros_type + " sample too short for its header, or not little-endian CDR");
  if (ros_type == "sensor_msgs/msg/PointCloud2" && hasAbsolutePointTimes(topic, sample)) {
    shiftPointTimes(sample, offset_);  // before its stamp moves
  }
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::memcpy(&sec, &sample.data[kEncapsulation], 4);
  std::memcpy(&nanosec, &sample.data[kEncapsulation + 4], 4);
  const std::int64_t ns = sec * kNsPerSecond + nanosec + offset_.ns;
  sec = static_cast<std::int32_t>(ns / kNsPerSecond);
  nanosec = static_cast<std::uint32_t>(ns % kNsPerSecond);
  std::memcpy(&sample.data[kEncapsulation], &sec, 4);
  std::memcpy(&sample.data[kEncapsulation + 4], &nanosec, 4);
  return true;
}

}  // namespace uampc::recording
