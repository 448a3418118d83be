// What a rig calibration does to the LO: the simulated motorized LiDAR driven along a world's path
// with the rig it truly is, and the LO core de-rotating with the rig it believes, as on a real rig
// (docs/results/calibration.md, "What it does to the LO").
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "uampc/evaluator/absolute_trajectory_error.hpp"
#include "uampc/frames/motorized_lidar.hpp"

namespace uampc::calibration {

struct LoDrive {
  std::string source;   // lo_replay's SOURCE: corridor, campus, multilevel or an MCD trajectory file
  std::uint64_t seed = 1;
  double seconds = 60.0;      // of the path, from its start
  double motor_speed = 3.6;   // rad/s, constant
  double range_noise = 0.02;  // m, the scenes'
};

struct LoDriveResult {
  evaluator::AteRmse ate;                // m, over the frames registered
  std::optional<double> runaway_at;      // s, the evaluator's runaway test
  std::size_t frames = 0;
};

// The raycaster casts with `truth`; the encoder reads the truth's rotor angle plus its zero, on its
// clock (Eq. 1's theta, frames::rotorReading's convention); the LO (LiDAR-only, its defaults,
// started at the ground truth) takes the encoder's readings back to rotor angles with `believed`,
// as the lo component does.
LoDriveResult driveLo(const LoDrive& drive, const frames::MotorLidarCalibration& truth,
                      const frames::MotorLidarCalibration& believed);

}  // namespace uampc::calibration
