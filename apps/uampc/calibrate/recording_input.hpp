// A recording as `uampc record` writes it (MCAP, rosbag2's CDR), read into what the rig
// calibration needs: the scans, the encoder's states and, when recorded, the ground-truth pose.
#pragma once

#include <string>

#include "uampc/calibration/rig_recording.hpp"

namespace uampc::app {

struct RecordingTopics {
  std::string scans = "/lidar/points";
  std::string motor = "/motor/state";
  std::string ground_truth = "/ground_truth/pose";  // read when present
};

// Throws std::runtime_error naming the file on an unreadable file or undecodable sample, and
// naming the topics the recording does have when a needed one is missing.
calibration::RigRecording readRigRecording(const std::string& path, const RecordingTopics& topics);

}  // namespace uampc::app
