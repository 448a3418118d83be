// Generated ground-truth paths: a smooth walk through waypoints at constant speed.
//
// Corners are rounded (each corner's legs are cut back by up to corner_cut metres and joined by a
// parabolic arc), the heading follows the direction of travel
// (roll and pitch zero, z up), and poses are sampled at rate_hz; a Trajectory interpolates between.
#pragma once

#include <vector>

#include "uampc/world/trajectory.hpp"

namespace uampc::world {

struct GeneratedPathConfig {
  double speed = 1.5;       // m/s along the path
  double rate_hz = 10.0;    // pose samples per second
  bool closed = false;      // return from the last waypoint to the first
  int laps = 1;             // closed paths only
  double corner_cut = 5.0;  // m cut off each leg of a corner (at most half a leg)
  double start_time = 0.0;  // s
};

// Throws std::invalid_argument for fewer than two waypoints or a non-positive speed or rate.
Trajectory pathThroughWaypoints(const std::vector<Eigen::Vector3d>& waypoints,
                                const GeneratedPathConfig& config);

}  // namespace uampc::world
