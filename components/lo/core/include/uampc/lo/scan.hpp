// One LiDAR frame as the driver delivers it, and a point once the motor has been taken out of it.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace uampc::lo {

// A frame in the LiDAR frame L. Each point carries its own time: stamp + time_offsets[i] (s).
struct Scan {
  double stamp = 0.0;                     // s
  std::vector<Eigen::Vector3f> points_L;  // m, LiDAR frame
  std::vector<float> time_offsets;        // s since stamp, one per point
};

// A point in the base frame B as it was at its own time, tau seconds relative to the scan's
// reference time (the scan end, so tau <= 0).
struct TimedPoint {
  Eigen::Vector3d p_B;
  double tau = 0.0;
};

}  // namespace uampc::lo
