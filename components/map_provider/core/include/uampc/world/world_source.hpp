// Which world and which ground-truth trajectory a scene serves, from map_provider's parameters
// (here, outside the component, so that development tools build the very same worlds without DDS).
#pragma once

#include <cstdint>
#include <string>

#include "uampc/world/map_io.hpp"
#include "uampc/world/trajectory.hpp"
#include "uampc/world/triangle_mesh.hpp"

namespace uampc::world {

struct WorldSettings {
  std::string world = "campus";  // campus | corridor | multilevel | around_trajectory | file
  std::string map_file;          // world = file: PCD or PLY
  double map_voxel_size = 0.0;
  Eigen::Vector3f map_offset = Eigen::Vector3f::Zero();
  std::string trajectory = "generated";  // generated | file
  std::string trajectory_file;           // MCD CSV (.csv) or TUM
  std::string attitude = "from_file";    // from_file | yaw_only | identity
  std::string interpolation = "linear";  // linear | smooth (see world::Interpolation)
  double smoothing = 0.0;                // s: moving-average window over file poses (0: none)
  double trajectory_start = 0.0;         // s skipped at the start of a file trajectory
  double path_speed = 1.5;               // m/s, generated paths
  int path_laps = 1;
  double base_height = 1.0;            // m above the ground, generated paths
  int campus_poor_rows = 1;            // campus: rows of blocks with poor geometry (0: all rich)
  double corridor_door_spacing = 0.0;  // corridor: m between door recesses (0: plain walls)
  // around_trajectory: how built-up the path's stretches are (density_profile.hpp): a named profile
  // (rich | mixed | poor), or open_fraction in [0, 1] overriding it (kUseProfile: the profile's).
  std::string density_profile = "rich";
  double open_fraction = kUseProfile;
  static constexpr double kUseProfile = -1.0;
  std::uint64_t seed = 1;
};

struct World {
  TriangleMesh mesh;
  std::vector<Eigen::Vector3f> points;  // point maps only
  Trajectory trajectory;                // starts at time 0 (sim time)
  std::string description;
  std::vector<std::string> warnings;
};

// Builds the world and the trajectory; throws std::runtime_error with a message a user can act on.
World buildWorld(const WorldSettings& settings);

}  // namespace uampc::world
