#include "uampc/calibration/rig_recording.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace uampc::calibration {
namespace {

std::string formatted(double value, int precision) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(precision);
  s << value;
  return s.str();
}

// The encoder's angles while the scans were taken: [min, max] over the readings within them.
std::optional<std::pair<double, double>> angleSpan(const RigRecording& r) {
  const double from = r.scans.front().stamp;
  double to = r.scans.back().stamp;
  for (const float offset : r.scans.back().time_offsets) to = std::max(to, r.scans.back().stamp + offset);
  std::optional<std::pair<double, double>> span;
  for (const auto& reading : r.encoder) {
    if (reading.time < from || reading.time > to) continue;
    if (!span) span = {reading.theta, reading.theta};
    span->first = std::min(span->first, reading.theta);
    span->second = std::max(span->second, reading.theta);
  }
  return span;
}

std::optional<std::string> baseMotion(const RigRecording& r, const RecordingLimits& limits) {
  if (r.base_poses.empty()) return std::nullopt;
  const Eigen::Isometry3d& first = r.base_poses.front().T_WB;
  double moved = 0.0, turned = 0.0;
  for (const auto& pose : r.base_poses) {
    const Eigen::Isometry3d delta = first.inverse() * pose.T_WB;
    moved = std::max(moved, delta.translation().norm());
    turned = std::max(turned, Eigen::AngleAxisd(delta.linear()).angle());
  }
  if (moved <= limits.max_base_translation && turned <= limits.max_base_rotation) return std::nullopt;
  return "the base moved during the recording (its ground-truth pose moved " + formatted(moved, 3) + " m and turned " +
         formatted(turned * 180.0 / M_PI, 2) + " deg; at most " + formatted(limits.max_base_translation, 3) +
         " m and " + formatted(limits.max_base_rotation * 180.0 / M_PI, 2) +
         " deg are allowed): calibrate from a recording of the rig standing still";
}

}  // namespace

std::optional<std::string> whyNotCalibratable(const RigRecording& r, const RecordingLimits& limits) {
  std::size_t points = 0;
  for (const auto& scan : r.scans) points += scan.points.size();
  if (r.scans.empty() || points == 0) return std::string("the recording has no LiDAR scans with points");
  if (r.encoder.empty()) return std::string("the recording has no motor states (encoder readings)");
  const auto span = angleSpan(r);
  const double turned = span ? span->second - span->first : 0.0;
  if (turned < limits.min_turn) {
    return "the motor turned " + formatted(turned * 180.0 / M_PI, 1) + " deg while the scans were taken; " +
           "a calibration needs at least " + formatted(limits.min_turn * 180.0 / M_PI, 0) +
           " deg (one full turn), so that every part of the scene is seen at different motor angles";
  }
  return baseMotion(r, limits);
}

}  // namespace uampc::calibration
