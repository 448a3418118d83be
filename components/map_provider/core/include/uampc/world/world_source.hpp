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
  // Point-map worlds (docs/decisions/point-map-splats.md): > 0 turns any world into a point map of
  // this resolution, m (a loaded point map is downsampled to it); 0 keeps meshes as meshes.
  double point_map_resolution = 0.0;
  // m, the half-width of each point's ray-facing splat; 0: kReferenceSplatFactor times the map's
  // resolution, as the reference simulator draws them.
  double splat_radius = 0.0;
  // s the rig stands still at the trajectory's first pose before it eases into the path over
  // kStartEaseTime (0: it moves from the start). See docs/decisions/start-hold.md.
  double start_hold = 0.0;
  std::uint64_t seed = 1;
};

// The reference simulator's splat half-width per unit of map resolution: MARSIM's
// cover_dis = 0.55 * sqrt(3) * downsample_resolution.
inline constexpr double kReferenceSplatFactor = 0.9526279441628825;  // 0.55 * sqrt(3)
// The splat radius of a point map whose resolution nobody gave (the spheres' radius before splats).
inline constexpr double kUnknownResolutionSplatRadius = 0.05;
// A world turned into a point map may have at most this many points, estimated from its surface
// before anything is built: the build samples 10 points per resolution^2 of surface, and the
// campus at 0.1 m (12.7 million points) took 68 s to start, past the launcher's start timeout,
// where NTU's world at 0.2 m (7.6 million, the largest a shipped experiment uses) starts
// (docs/user/scenes.md, "Point-map worlds and a held start").
inline constexpr double kMaxPointMapPoints = 8e6;
// s over which a held start accelerates evenly into the trajectory's own speed.
inline constexpr double kStartEaseTime = 2.0;

struct World {
  TriangleMesh mesh;
  std::vector<Eigen::Vector3f> points;  // point maps only
  float point_radius = static_cast<float>(kUnknownResolutionSplatRadius);  // m, each point's splat
  Trajectory trajectory;                // starts at time 0 (sim time)
  std::string description;
  std::vector<std::string> warnings;
};

// Builds the world and the trajectory; throws std::runtime_error with a message a user can act on.
World buildWorld(const WorldSettings& settings);

}  // namespace uampc::world
