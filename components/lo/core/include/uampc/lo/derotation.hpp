// De-rotation: take the spinning motor out of a scan (docs/dev/architecture.md section 1, Eq. 1).
//
//   p_B(t_i) = R_BM(theta(t_i)) * ( R_ML * p_L + r_ML )
//
// the inner bracket of Eq. 1, evaluated for every point with the encoder angle interpolated at
// that point's own time t_i = stamp + time_offsets[i]. The motor turns by ~0.36 rad during a
// 0.1 s frame at 3.6 rad/s, so one angle per frame would smear the scan by metres at range.
#pragma once

#include <cstddef>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/lo/scan.hpp"

namespace uampc::lo {

struct DerotatedScan {
  std::vector<TimedPoint> points;      // base frame at each point's own time, tau <= 0
  double end_time = 0.0;               // s, time of the latest kept point: the reference time
  std::size_t dropped_non_finite = 0;  // NaN or inf coordinates or time offsets
  std::size_t dropped_range = 0;       // range (in L) outside [min_range, max_range]
  std::size_t dropped_outside_motor_track = 0;  // no encoder reading around the point's time
};

// Throws std::invalid_argument when points_L and time_offsets differ in size.
DerotatedScan derotate(const Scan& scan, const frames::MotorAngleTrack& motor,
                       const frames::MotorLidarCalibration& calibration, double min_range,
                       double max_range);

}  // namespace uampc::lo
