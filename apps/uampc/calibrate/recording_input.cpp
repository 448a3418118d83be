#include "calibrate/recording_input.hpp"

#include <stdexcept>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/mcap/mcap.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/time.hpp"
#include "uampc/runtime/typed_sample.hpp"

namespace uampc::app {
namespace {

std::string topicList(const mcap::Reader& reader) {
  std::string list;
  for (const auto& channel : reader.channels()) list += (list.empty() ? "" : ", ") + channel.topic;
  return list.empty() ? "none" : list;
}

template <typename Message>
Message decoded(const mcap::MessageView& view, const std::string& path) {
  Message message;
  if (!decodeSample(SerializedMessage{std::vector<std::uint8_t>(view.data, view.data + view.size)}, message)) {
    throw std::runtime_error(path + ": a sample on " + view.channel->topic + " that does not decode as " +
                             MessageType<Message>::kRosName);
  }
  return message;
}

calibration::RecordedScan scanOf(const sensor_msgs::msg::PointCloud2& cloud) {
  const pointcloud::TimeField time_field = pointcloud::findTimeField(cloud);
  const pointcloud::ScanPoints points = pointcloud::readCloud(cloud, &time_field);
  calibration::RecordedScan scan;
  scan.stamp = fromMsg(cloud.header().stamp()).seconds();
  scan.points = points.positions;
  scan.time_offsets = points.time_offsets;
  scan.time_offsets.resize(scan.points.size(), 0.0f);  // no time field: every point at the stamp
  return scan;
}

// The encoder's rate where the states carry none: the angle's slope between neighbours.
void fillMissingRates(std::vector<frames::MotorReading>& encoder, bool rates_given) {
  if (rates_given || encoder.size() < 2) return;
  for (std::size_t i = 0; i < encoder.size(); ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 < encoder.size() ? i + 1 : i;
    encoder[i].omega = (encoder[b].theta - encoder[a].theta) / (encoder[b].time - encoder[a].time);
  }
}

}  // namespace

calibration::RigRecording readRigRecording(const std::string& path, const RecordingTopics& topics) {
  mcap::Reader reader(path);
  if (!reader.findChannel(topics.scans)) {
    throw std::runtime_error(path + " has no LiDAR scans on " + topics.scans + " (its topics: " + topicList(reader) +
                             "; --scan-topic names another)");
  }
  if (!reader.findChannel(topics.motor)) {
    throw std::runtime_error(path + " has no motor states on " + topics.motor + " (its topics: " + topicList(reader) +
                             "; --motor-topic names another)");
  }
  calibration::RigRecording recording;
  bool rates_given = true;
  std::vector<std::string> wanted = {topics.scans, topics.motor};
  if (reader.findChannel(topics.ground_truth)) wanted.push_back(topics.ground_truth);
  reader.forEachMessage(wanted, 0, [&](const mcap::MessageView& view) {
    if (view.channel->topic == topics.scans) {
      recording.scans.push_back(scanOf(decoded<sensor_msgs::msg::PointCloud2>(view, path)));
    } else if (view.channel->topic == topics.motor) {
      const auto state = decoded<sensor_msgs::msg::JointState>(view, path);
      if (state.position().empty() || !std::isfinite(state.position()[0])) return true;
      const double t = fromMsg(state.header().stamp()).seconds();
      if (!recording.encoder.empty() && t <= recording.encoder.back().time) return true;
      rates_given = rates_given && !state.velocity().empty();
      recording.encoder.push_back({t, state.position()[0], state.velocity().empty() ? 0.0 : state.velocity()[0]});
    } else {
      const auto pose = decoded<geometry_msgs::msg::PoseStamped>(view, path);
      if (adapters::isFinitePose(pose.pose())) {
        recording.base_poses.push_back({fromMsg(pose.header().stamp()).seconds(), adapters::toIsometry(pose.pose())});
      }
    }
    return true;
  });
  fillMissingRates(recording.encoder, rates_given);
  return recording;
}

}  // namespace uampc::app
