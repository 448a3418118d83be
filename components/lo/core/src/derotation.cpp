#include "uampc/lo/derotation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace uampc::lo {

DerotatedScan derotate(const Scan& scan, const frames::MotorAngleTrack& motor,
                       const frames::MotorLidarCalibration& calibration, double min_range,
                       double max_range) {
  if (scan.points_L.size() != scan.time_offsets.size()) {
    throw std::invalid_argument("lo::derotate: scan has " + std::to_string(scan.points_L.size()) +
                                " points but " + std::to_string(scan.time_offsets.size()) +
                                " time offsets; they must be one per point");
  }
  DerotatedScan out;
  out.points.reserve(scan.points_L.size());
  std::vector<double> times;
  times.reserve(scan.points_L.size());
  const double min_range2 = min_range * min_range;
  const double max_range2 = max_range * max_range;
  std::size_t motor_cursor = 0;  // the points come in time order: the encoder interval rarely changes
  for (std::size_t i = 0; i < scan.points_L.size(); ++i) {
    const Eigen::Vector3d p_L = scan.points_L[i].cast<double>();
    const float offset = scan.time_offsets[i];
    if (!p_L.allFinite() || !std::isfinite(offset)) {
      ++out.dropped_non_finite;
      continue;
    }
    const double range2 = p_L.squaredNorm();
    if (range2 < min_range2 || range2 > max_range2) {
      ++out.dropped_range;
      continue;
    }
    const double t = scan.stamp + static_cast<double>(offset);
    const std::optional<double> theta = motor.thetaAt(t, motor_cursor);
    if (!theta) {
      ++out.dropped_outside_motor_track;
      continue;
    }
    // Eq. 1, inner bracket, at the point's own encoder angle.
    out.points.push_back({frames::lidarToBase(p_L, *theta, calibration), 0.0});
    times.push_back(t);
  }
  if (out.points.empty()) {
    out.end_time = scan.stamp;
    return out;
  }
  out.end_time = times.front();
  for (double t : times) out.end_time = std::max(out.end_time, t);
  for (std::size_t i = 0; i < times.size(); ++i) out.points[i].tau = times[i] - out.end_time;
  return out;
}

}  // namespace uampc::lo
