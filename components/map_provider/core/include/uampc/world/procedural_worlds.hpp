// Procedural worlds, generated from a seed: the same config and seed give the same mesh on every
// machine (SeededRandom, no std distributions). Every world is a TriangleMesh with z up and the
// ground at z = 0 (around-trajectory: the ground follows the trajectory's height).
//
//   campus:            a grid of blocks separated by streets; rich blocks hold buildings with
//   facade
//                      detail, trees, poles and low walls, poor blocks (a row of them) only plain
//                      walls or lawn, so a loop along the streets passes rich and poor stretches.
//   corridor:          a long plain corridor (300 m by default), the classic degenerate case.
//   multilevel:        a building of several storeys joined by a stairwell.
//   around-trajectory: buildings, trees and walls scattered around a given path, kept off it by a
//                      clearance, on a ground that follows the path's height; with a density
//                      profile (density_profile.hpp), stretches of the path are open instead: a
//                      lawn, a car park, one long plain wall or a street between two of them.
#pragma once

#include <cstdint>
#include <vector>

#include "uampc/world/density_profile.hpp"
#include "uampc/world/triangle_mesh.hpp"

namespace uampc::world {

struct CampusConfig {
  int blocks = 3;              // blocks along x and along y
  double block_size = 60.0;    // m, side of a square block
  double street_width = 14.0;  // m
  int poor_rows = 1;           // the northmost rows of blocks hold poor geometry only
  double tree_spacing = 12.0;  // m, street trees along rich blocks
  double pole_spacing = 20.0;  // m, street-light poles along every block
  double margin = 40.0;        // m of ground beyond the outermost street
  int segments = 10;           // facets of cylinders and cones
};

struct CorridorConfig {
  double length = 300.0;  // m, along x from x = 0
  double width = 3.0;     // m, centred on y = 0
  double height = 3.0;    // m
  // Door recesses every door_spacing metres on alternating sides; 0 keeps the walls plain.
  // A plain corridor constrains nothing along its axis between its end walls; the recesses'
  // sides are the only surfaces facing along it (as doors are in a real office corridor).
  double door_spacing = 0.0;
  double door_width = 1.0;   // m
  double door_height = 2.1;  // m
  double door_depth = 0.3;   // m, from the wall's face to the door leaf
};

struct MultilevelConfig {
  int floors = 3;
  double floor_height = 3.5;      // m
  double length = 40.0;           // m, along x from x = 0
  double width = 20.0;            // m, along y from y = 0
  double slab_thickness = 0.3;    // m
  double stairwell_length = 7.0;  // m, at the +x end of the building, along the -y wall
  double stairwell_width = 3.0;   // m
  double column_spacing = 8.0;    // m; interior columns give the LO something to hold on to
  double ground_margin = 20.0;    // m of ground around the building
};

struct AroundTrajectoryConfig {
  double clearance = 4.0;              // m, nothing closer than this to the path (horizontally)
  double margin = 40.0;                // m of ground beyond the path's bounding box
  double band = 30.0;                  // m: objects stand within this of the path (beyond the clearance)
  double base_height = 1.0;            // m, height of the path above the ground
  double buildings_per_hectare = 3.0;  // per hectare of the band along the path
  double trees_per_hectare = 12.0;
  double walls_per_hectare = 2.0;
  double ground_cell = 5.0;  // m, grid of the ground height field
  int segments = 8;
  // Which stretches of the path are built-up (the objects above) and which open. An object
  // belongs to the stretch of its nearest path sample (on the path's first pass within
  // clearance + band of it, where the path comes back); objects of open stretches are not built.
  DensityProfileConfig density;
  // Open stretches' furniture, all kept off the path by the clearance like everything else.
  double car_spacing = 15.0;   // m of car-park stretch per parked car (a 4.5 x 1.8 x 1.5 m box)
  double car_reach = 12.0;     // m beyond the clearance within which cars park
  double wall_segment = 10.0;  // m, long walls are straight pieces this long following the path
};

TriangleMesh makeCampus(const CampusConfig& config, std::uint64_t seed);
TriangleMesh makeCorridor(const CorridorConfig& config);
TriangleMesh makeMultilevel(const MultilevelConfig& config);
TriangleMesh makeAroundTrajectory(const std::vector<Eigen::Vector3d>& path, const AroundTrajectoryConfig& config,
                                  std::uint64_t seed);

// Street centre lines of the campus: the ring around the centre block, counter-clockwise,
// at height base_height, as closed waypoints (last != first). Use with pathThroughWaypoints.
std::vector<Eigen::Vector3d> campusLoopWaypoints(const CampusConfig& config, double base_height);

// Along the corridor's axis, from 2 m after its start to 2 m before its end.
std::vector<Eigen::Vector3d> corridorWaypoints(const CorridorConfig& config, double base_height);

// Through every floor: a tour around each storey, then up the switch-back stairs to the next.
std::vector<Eigen::Vector3d> multilevelWaypoints(const MultilevelConfig& config, double base_height);

}  // namespace uampc::world
