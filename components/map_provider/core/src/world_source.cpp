#include "uampc/world/world_source.hpp"

#include <cstdio>
#include <stdexcept>

#include "uampc/world/generated_paths.hpp"
#include "uampc/world/point_sampling.hpp"
#include "uampc/world/procedural_worlds.hpp"
#include "uampc/world/short_number.hpp"
#include "uampc/world/trajectory_io.hpp"

namespace uampc::world {

namespace {

Trajectory readFileTrajectory(const WorldSettings& s) {
  if (s.trajectory_file.empty()) throw std::runtime_error("trajectory: file needs trajectory_file");
  const bool mcd = s.trajectory_file.size() > 4 && s.trajectory_file.substr(s.trajectory_file.size() - 4) == ".csv";
  // MCD's quaternions describe a z-down body frame: forMcd() turns it z-up (pi about x).
  TrajectoryReadOptions options = mcd ? TrajectoryReadOptions::forMcd() : TrajectoryReadOptions{};
  options.attitude = attitudeModeFromName(s.attitude);
  options.start_at_zero = true;
  Trajectory t = readTrajectory(s.trajectory_file, options);
  if (s.trajectory_start > 0) {
    if (s.trajectory_start >= t.duration()) {
      throw std::runtime_error("trajectory_start " + std::to_string(s.trajectory_start) + " s is beyond the end of " +
                               s.trajectory_file + " (" + std::to_string(t.duration()) + " s)");
    }
    std::vector<TimedPose> kept{
        {0.0, t.poseAt(s.trajectory_start).translation(), Eigen::Quaterniond(t.poseAt(s.trajectory_start).linear())}};
    for (const auto& p : t.poses()) {
      if (p.time > s.trajectory_start) kept.push_back({p.time - s.trajectory_start, p.position, p.orientation});
    }
    t = Trajectory(kept);
  }
  if (s.smoothing > 0) t = movingAverage(t, s.smoothing);
  return Trajectory(t.poses(), interpolationFromName(s.interpolation));
}

// The around-trajectory world's density profile: the named profile's open fraction, or the
// explicit one; either refused with a message naming the parameter.
DensityProfileConfig densityProfileOf(const WorldSettings& s) {
  DensityProfileConfig profile;
  try {
    profile.open_fraction = openFractionOfProfile(s.density_profile);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("density_profile: ") + e.what());
  }
  if (s.open_fraction != WorldSettings::kUseProfile) {
    if (!(s.open_fraction >= 0.0 && s.open_fraction <= 1.0)) {
      throw std::runtime_error("open_fraction must be between 0 and 1 (share of path length that is open), or " +
                               shortNumber(WorldSettings::kUseProfile) + " for density_profile's, got " +
                               shortNumber(s.open_fraction));
    }
    profile.open_fraction = s.open_fraction;
  }
  return profile;
}

Trajectory generatedPath(const std::vector<Eigen::Vector3d>& waypoints, bool closed, const WorldSettings& s) {
  GeneratedPathConfig config;
  config.speed = s.path_speed;
  config.closed = closed;
  config.laps = s.path_laps;
  return pathThroughWaypoints(waypoints, config);
}

// Any world as a point map of the scene's resolution, each point a splat (see
// docs/decisions/point-map-splats.md); a mesh world with no resolution stays a mesh.
void applyPointMapSettings(const WorldSettings& s, World& w) {
  if (s.point_map_resolution > 0.0 && !w.mesh.empty()) {
    const double expected = expectedPointMapSize(w.mesh.area(), s.point_map_resolution);
    if (expected > kMaxPointMapPoints) {
      throw std::runtime_error("point_map_resolution " + shortNumber(s.point_map_resolution) + " m would make about " +
                               shortNumber(std::round(expected / 1e6)) + " million points of this world's " +
                               shortNumber(std::round(w.mesh.area())) + " m2 of surface, more than " +
                               shortNumber(kMaxPointMapPoints / 1e6) + " million: choose a coarser resolution");
    }
    w.points = surfacePointMap(w.mesh, s.point_map_resolution, s.seed);
    w.mesh = TriangleMesh{};
  } else if (s.point_map_resolution > 0.0) {
    w.points = voxelDownsample(w.points, s.point_map_resolution);
  }
  if (w.points.empty()) return;
  const double resolution = s.point_map_resolution > 0.0 ? s.point_map_resolution : s.map_voxel_size;
  const double radius = s.splat_radius > 0.0 ? s.splat_radius
                        : resolution > 0.0   ? kReferenceSplatFactor * resolution
                                             : kUnknownResolutionSplatRadius;
  w.point_radius = static_cast<float>(radius);
}

}  // namespace

World buildWorld(const WorldSettings& s) {
  World w;
  const bool from_file = s.trajectory == "file";
  if (from_file) w.trajectory = readFileTrajectory(s);
  if (s.world == "campus") {
    CampusConfig config;
    config.poor_rows = s.campus_poor_rows;
    w.mesh = makeCampus(config, s.seed);
    if (!from_file) w.trajectory = generatedPath(campusLoopWaypoints(config, s.base_height), true, s);
  } else if (s.world == "corridor") {
    CorridorConfig config;
    if (s.corridor_door_spacing != 0.0 && !(s.corridor_door_spacing >= 2.0)) {
      throw std::runtime_error(
          "corridor_door_spacing must be 0 (plain walls) or at least 2 m (1 m doors with wall "
          "between them), got " +
          std::to_string(s.corridor_door_spacing));
    }
    config.door_spacing = s.corridor_door_spacing;
    w.mesh = makeCorridor(config);
    if (!from_file) w.trajectory = generatedPath(corridorWaypoints(config, s.base_height), false, s);
  } else if (s.world == "multilevel") {
    MultilevelConfig config;
    w.mesh = makeMultilevel(config);
    if (!from_file) w.trajectory = generatedPath(multilevelWaypoints(config, s.base_height), false, s);
  } else if (s.world == "around_trajectory") {
    if (!from_file) throw std::runtime_error("world: around_trajectory needs trajectory: file and a trajectory_file");
    std::vector<Eigen::Vector3d> path;
    for (const auto& p : w.trajectory.poses()) path.push_back(p.position);
    AroundTrajectoryConfig config;
    config.density = densityProfileOf(s);
    w.mesh = makeAroundTrajectory(path, config, s.seed);
  } else if (s.world == "file") {
    if (s.map_file.empty()) throw std::runtime_error("world: file needs map_file (a PCD or PLY map)");
    if (!from_file) throw std::runtime_error("world: file needs trajectory: file and a trajectory_file");
    MapLoadOptions options;
    options.voxel_size = s.map_voxel_size;
    options.offset = s.map_offset;
    LoadedMap map = loadMap(s.map_file, options);
    w.mesh = std::move(map.mesh);
    w.points = std::move(map.points);
    w.warnings = std::move(map.warnings);
    if (w.mesh.empty() && w.points.empty()) throw std::runtime_error(s.map_file + ": the map has no usable geometry");
  } else {
    throw std::runtime_error("unknown world '" + s.world + "'");
  }
  applyPointMapSettings(s, w);
  w.trajectory = withHeldStart(w.trajectory, s.start_hold, kStartEaseTime);
  const std::string profile = s.world != "around_trajectory" ? ""
                              : s.open_fraction == WorldSettings::kUseProfile
                                  ? ", density profile " + s.density_profile
                                  : ", open fraction " + shortNumber(s.open_fraction);
  w.description = s.world + (s.world == "file" ? " " + s.map_file : " seed " + std::to_string(s.seed)) + profile +
                  ", trajectory " + (from_file ? s.trajectory_file : "generated") +
                  (w.points.empty() ? "" : ", point map with splats of " + shortNumber(w.point_radius) + " m") +
                  (s.start_hold > 0.0 ? ", held still for " + shortNumber(s.start_hold) + " s" : "");
  return w;
}

}  // namespace uampc::world
