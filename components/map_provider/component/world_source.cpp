#include "world_source.hpp"

#include <stdexcept>

#include "uampc/world/generated_paths.hpp"
#include "uampc/world/procedural_worlds.hpp"
#include "uampc/world/trajectory_io.hpp"

namespace uampc::map_provider {

namespace {

world::Trajectory readFileTrajectory(const WorldSettings& s) {
  if (s.trajectory_file.empty()) throw std::runtime_error("trajectory: file needs trajectory_file");
  const bool mcd = s.trajectory_file.size() > 4 && s.trajectory_file.substr(s.trajectory_file.size() - 4) == ".csv";
  // MCD's quaternions describe a z-down body frame: forMcd() turns it z-up (pi about x).
  world::TrajectoryReadOptions options = mcd ? world::TrajectoryReadOptions::forMcd() : world::TrajectoryReadOptions{};
  options.attitude = world::attitudeModeFromName(s.attitude);
  options.start_at_zero = true;
  world::Trajectory t = world::readTrajectory(s.trajectory_file, options);
  if (s.trajectory_start > 0) {
    if (s.trajectory_start >= t.duration()) {
      throw std::runtime_error("trajectory_start " + std::to_string(s.trajectory_start) + " s is beyond the end of " +
                               s.trajectory_file + " (" + std::to_string(t.duration()) + " s)");
    }
    std::vector<world::TimedPose> kept{{0.0, t.poseAt(s.trajectory_start).translation(),
                                        Eigen::Quaterniond(t.poseAt(s.trajectory_start).linear())}};
    for (const auto& p : t.poses()) {
      if (p.time > s.trajectory_start) kept.push_back({p.time - s.trajectory_start, p.position, p.orientation});
    }
    t = world::Trajectory(kept);
  }
  if (s.smoothing > 0) t = world::movingAverage(t, s.smoothing);
  return world::Trajectory(t.poses(), world::interpolationFromName(s.interpolation));
}

world::Trajectory generatedPath(const std::vector<Eigen::Vector3d>& waypoints, bool closed, const WorldSettings& s) {
  world::GeneratedPathConfig config;
  config.speed = s.path_speed;
  config.closed = closed;
  config.laps = s.path_laps;
  return world::pathThroughWaypoints(waypoints, config);
}

}  // namespace

World buildWorld(const WorldSettings& s) {
  World w;
  const bool from_file = s.trajectory == "file";
  if (from_file) w.trajectory = readFileTrajectory(s);
  if (s.world == "campus") {
    world::CampusConfig config;
    config.poor_rows = s.campus_poor_rows;
    w.mesh = world::makeCampus(config, s.seed);
    if (!from_file) w.trajectory = generatedPath(world::campusLoopWaypoints(config, s.base_height), true, s);
  } else if (s.world == "corridor") {
    world::CorridorConfig config;
    w.mesh = world::makeCorridor(config);
    if (!from_file) w.trajectory = generatedPath(world::corridorWaypoints(config, s.base_height), false, s);
  } else if (s.world == "multilevel") {
    world::MultilevelConfig config;
    w.mesh = world::makeMultilevel(config);
    if (!from_file) w.trajectory = generatedPath(world::multilevelWaypoints(config, s.base_height), false, s);
  } else if (s.world == "around_trajectory") {
    if (!from_file) throw std::runtime_error("world: around_trajectory needs trajectory: file and a trajectory_file");
    std::vector<Eigen::Vector3d> path;
    for (const auto& p : w.trajectory.poses()) path.push_back(p.position);
    w.mesh = world::makeAroundTrajectory(path, world::AroundTrajectoryConfig{}, s.seed);
  } else if (s.world == "file") {
    if (s.map_file.empty()) throw std::runtime_error("world: file needs map_file (a PCD or PLY map)");
    if (!from_file) throw std::runtime_error("world: file needs trajectory: file and a trajectory_file");
    world::MapLoadOptions options;
    options.voxel_size = s.map_voxel_size;
    options.offset = s.map_offset;
    world::LoadedMap map = world::loadMap(s.map_file, options);
    w.mesh = std::move(map.mesh);
    w.points = std::move(map.points);
    w.warnings = std::move(map.warnings);
    if (w.mesh.empty() && w.points.empty()) throw std::runtime_error(s.map_file + ": the map has no usable geometry");
  } else {
    throw std::runtime_error("unknown world '" + s.world + "'");
  }
  w.description = s.world + (s.world == "file" ? " " + s.map_file : " seed " + std::to_string(s.seed)) +
                  ", trajectory " + (from_file ? s.trajectory_file : "generated");
  return w;
}

}  // namespace uampc::map_provider
