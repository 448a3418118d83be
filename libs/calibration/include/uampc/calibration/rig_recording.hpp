// What a rig calibration is computed from: a recording of the rig standing still while the motor
// turns (docs/user/calibration.md), as plain data, without DDS or a file format.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"

namespace uampc::calibration {

// One LiDAR frame: points in the LiDAR frame, each with its time since the stamp.
struct RecordedScan {
  double stamp = 0.0;                   // s, the LiDAR's clock
  std::vector<Eigen::Vector3f> points;  // m, LiDAR frame
  std::vector<float> time_offsets;      // s since stamp, one per point
};

struct BasePose {
  double time = 0.0;
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
};

struct RigRecording {
  std::vector<RecordedScan> scans;
  std::vector<frames::MotorReading> encoder;  // as the encoder read them, in increasing time
  std::vector<BasePose> base_poses;           // ground truth, when the recording has it
};

// What the checks before an estimation allow.
struct RecordingLimits {
  double min_turn = 2.0 * 3.14159265358979323846;  // rad the motor must turn during the scans
  double max_base_translation = 0.01;              // m the base may move (ground truth)
  double max_base_rotation = 0.002;                // rad the base may turn (ground truth)
};

// Why the recording cannot calibrate the rig (no scans, no motor states, less than a turn, a base
// that moved), as a message naming which; nothing when it can.
std::optional<std::string> whyNotCalibratable(const RigRecording& recording, const RecordingLimits& limits = {});

}  // namespace uampc::calibration
