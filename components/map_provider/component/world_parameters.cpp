#include "world_parameters.hpp"

#include <string>
#include <vector>

#include "uampc/world/density_profile.hpp"

namespace uampc {
namespace {

std::vector<std::string> profileNames() {
  std::vector<std::string> names;
  for (const auto& p : world::kDensityProfiles) names.emplace_back(p.name);
  return names;
}

// "rich 0, mixed 0.4, poor 0.7" from the profiles themselves, so the docs cannot drift from the code.
std::string profileFractions() {
  std::string text;
  for (const auto& p : world::kDensityProfiles) {
    text += (text.empty() ? "" : ", ") + std::string(p.name) + " " + formatNumber(p.open_fraction);
  }
  return text;
}

}  // namespace

void bindWorldParameters(ParameterBinding& b, world::WorldSettings& s) {
  b.bind("world", s.world, "campus, corridor, multilevel, around_trajectory or file")
      .oneOf({"campus", "corridor", "multilevel", "around_trajectory", "file"});
  b.bind("map_voxel_size", s.map_voxel_size, "voxel downsampling of point maps, m (0: none)").between(0.0, 10.0);
  b.bind("trajectory", s.trajectory, "generated (a path through the world) or file").oneOf({"generated", "file"});
  b.bind("attitude", s.attitude, "from_file (MCD: z-down frame turned z-up), yaw_only or identity")
      .oneOf({"from_file", "yaw_only", "identity"});
  b.bind("interpolation", s.interpolation,
         "between trajectory samples: linear (position) and slerp (attitude), or smooth (C1: cubic "
         "Hermite and SQUAD through the same samples; file trajectories only)")
      .oneOf({"linear", "smooth"});
  b.bind("smoothing", s.smoothing,
         "moving-average window over a file trajectory's poses, s (0: none); recorded ground truth "
         "carries attitude noise no vehicle performs")
      .between(0.0, 10.0);
  b.bind("trajectory_start", s.trajectory_start, "seconds of a file trajectory skipped at its start").atLeast(0.0);
  b.bind("path_speed", s.path_speed, "speed of generated paths, m/s").between(0.01, 50.0);
  b.bind("path_laps", s.path_laps, "laps of closed generated paths (campus)").between(1, 1000);
  b.bind("base_height", s.base_height, "height of generated paths above the ground, m").between(0.0, 100.0);
  b.bind("campus_poor_rows", s.campus_poor_rows, "world: campus: rows of blocks with poor geometry (0: all rich)")
      .between(0, 3);
  b.bind("corridor_door_spacing", s.corridor_door_spacing,
         "world: corridor: a 1 m door recessed 0.3 m every this many metres, alternating sides (0: plain "
         "walls, nothing fixes the position along the axis between the end walls)")
      .between(0.0, 1000.0);
  b.bind("density_profile", s.density_profile,
         "world: around_trajectory: how built-up the path's stretches (30-90 m, seeded) are; open stretches "
         "(lawn, car park, one long wall, a street of two) make up this share of the path: " +
             profileFractions() + " (chosen with constant motor speeds only, see docs/results/scenes-where-the-motor-matters.md)")
      .oneOf(profileNames());
  b.bind("open_fraction", s.open_fraction,
         "world: around_trajectory: share of path length that is open, 0 to 1, overriding density_profile "
         "(-1: density_profile's)")
      .between(-1.0, 1.0);
  b.bind("point_map_resolution", s.point_map_resolution,
         "> 0: the world becomes a point map of this resolution, m (surfaces sampled, one point per voxel; a "
         "loaded point map is downsampled to it), each point drawn as a splat facing the ray, as the "
         "reference simulator renders a dataset's map (0: meshes stay meshes; see "
         "docs/decisions/point-map-splats.md)")
      .between(0.05, 10.0)
      .orOff();
  b.bind("splat_radius", s.splat_radius,
         "half-width of each point map point's splat, m (0: 0.55 sqrt(3) times the map's resolution, "
         "point_map_resolution or else map_voxel_size, as the reference simulator; 0.05 m when neither is set)")
      .between(0.0, 5.0);
  b.bind("start_hold", s.start_hold,
         "s the rig stands still at the trajectory's first pose, then eases into the path over 2 s (0: "
         "it moves from the start; see docs/decisions/start-hold.md)")
      .between(0.0, 60.0);
}

}  // namespace uampc
