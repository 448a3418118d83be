// The rig's calibration from a recording of the rig standing still while the motor turns
// (docs/user/calibration.md): the scene seen at different motor angles must agree. Every scan is
// de-rotated with the candidate calibration (Eq. 1) into one map in the base frame; each term
// measures a point against the plane its neighbours from other motor angles form
// (plane_terms.hpp); Ceres minimises the terms under a Huber loss, the terms are found again
// with the new calibration, a few times. Only what a still base can see is estimated
// (rig_model.hpp); the rest is held at the believed values and said so.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/calibration/plane_terms.hpp"
#include "uampc/calibration/rig_recording.hpp"
#include "uampc/frames/motorized_lidar.hpp"

namespace uampc::calibration {

// A recording that cannot give a calibration, with the reason.
class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct EstimatorConfig {
  RecordingLimits limits;
  PlaneTermConfig terms;
  std::size_t max_points = 150000;  // sampled evenly from all scans
  double min_range = 0.5;           // m: nearer points are the rig itself
  double max_range = 60.0;          // m
  int outer_iterations = 6;         // terms found again, at most this often
  int solver_iterations = 20;       // Gauss-Newton steps per outer iteration, at most
  double huber = 0.05;              // m, where the loss turns linear
  // The clock offset is estimated only when the motor's rate varies by this much (standard
  // deviation over the scans, rad/s): at one speed it is a turn of the whole map.
  double min_rate_spread = 0.3;
  std::size_t min_terms = 300;  // fewer: too few planes
  // m: the calibrated map's points off its planes, third quartile, at most; more: a base or a scene
  // that moved (a plane along the motion hides it, so not the median), or a LiDAR that noisy.
  double max_off_plane = 0.04;
};

// One estimated or held parameter, in the rig block's units (degrees, m, s).
struct ParameterEstimate {
  std::string name;  // rig key part: "roll_deg", "pitch_deg", "yaw_deg", "x", "y", "z", ...
  double believed = 0.0;
  double value = 0.0;
  double stddev = 0.0;  // 0 when held
  bool estimated = false;
  std::string held_because;  // why it is held (empty when estimated)
};

struct CalibrationResult {
  frames::MotorLidarCalibration calibration;  // the believed one with the estimated parts replaced
  std::vector<ParameterEstimate> parameters;  // roll, pitch, yaw, x, y, z, encoder offset, time offset
  std::size_t points = 0, terms = 0;
  double median_distance_before = 0.0, median_distance_after = 0.0;  // m, |point off its plane|
  std::vector<double> distances_before, distances_after;             // m, signed, per term
  int outer_iterations = 0;
};

using Progress = std::function<void(const std::string& line)>;

// Throws CalibrationError when the recording cannot calibrate the rig (whyNotCalibratable, too
// few planes, a map that does not agree with itself even calibrated).
CalibrationResult estimateRig(const RigRecording& recording, const frames::MotorLidarCalibration& believed,
                              const EstimatorConfig& config = {}, const Progress& progress = {});

// A length as the estimator's messages and the report give it: "12.3 mm".
std::string millimetres(double metres);

}  // namespace uampc::calibration
