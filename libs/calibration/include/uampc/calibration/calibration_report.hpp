// A calibration's result for people and for scenes: the estimate with its standard deviations and
// what was held and why, the rig: block to paste into a scene, and the map's thickness on its
// planes before and after as an SVG figure.
#pragma once

#include <string>

#include "uampc/calibration/rig_estimator.hpp"

namespace uampc::calibration {

// Standard deviations above which an estimate is not trusted: it is reported as undetermined
// and the rig block keeps the believed value.
struct TrustLimits {
  double angle_deg = 0.2;
  double offset = 0.005;       // m
  double time_offset = 0.002;  // s
};

// Whether the parameter's standard deviation is within the limit of its kind.
bool trusted(const ParameterEstimate& p, const TrustLimits& limits);

// One line per parameter: estimated ones with value, standard deviation and change from the
// believed value; held ones with why; untrusted ones as undetermined.
std::string resultText(const CalibrationResult& result, const TrustLimits& limits);

// The rig: block (lidar_rotation_rpy_deg, lidar_offset, encoder_offset_deg, time_offset) with
// the trusted estimates and the believed values elsewhere; lidar_model is given by the caller.
std::string rigBlock(const CalibrationResult& result, const TrustLimits& limits, const std::string& lidar_model);

// Histograms of the map's distances off its planes before and after calibration.
std::string thicknessFigure(const CalibrationResult& result);

}  // namespace uampc::calibration
