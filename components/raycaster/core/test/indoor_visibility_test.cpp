// The indoor worlds must let the reference LiDAR see enough all along their generated paths,
// whatever a controller does: a scene in which every controller goes blind measures nothing.
// The multilevel world's stairwell once did (solid stair blocks within the Mid-360's 1.5 m
// minimum range left 12-53 points per frame for two seconds).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <tuple>

#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::raycaster {
namespace {

// Distinct 0.3 m voxels (the LO's scan downsampling) hit by a frame.
std::size_t occupiedVoxels(const Scan& scan) {
  std::set<std::tuple<int, int, int>> voxels;
  for (const auto& p : scan.points) {
    voxels.emplace(static_cast<int>(std::floor(p.position.x() / 0.3f)), static_cast<int>(std::floor(p.position.y() / 0.3f)),
                   static_cast<int>(std::floor(p.position.z() / 0.3f)));
  }
  return voxels.size();
}

// The fewest voxels of any frame cast every 0.5 s along the world's path, motor at 3.6 rad/s.
std::size_t fewestVoxelsAlongThePath(const std::string& world_name) {
  world::WorldSettings settings;
  settings.world = world_name;
  const world::World world = world::buildWorld(settings);
  RayCaster caster(world.mesh);
  frames::MotorAngleTrack motor(1e9);
  const double end = world.trajectory.endTime();
  for (double t = 0.0; t <= end; t += 0.005) motor.add({t, 3.6 * t, 3.6});
  std::size_t fewest = ~std::size_t{0};
  double at = 0.0;
  for (std::uint64_t k = 0; (k + 2) * 0.5 < end; ++k) {
    const double start = 0.5 * static_cast<double>(k);
    const std::size_t n = occupiedVoxels(caster.castFrame(k, start, world.trajectory, motor));
    if (n < fewest) {
      fewest = n;
      at = start;
    }
  }
  std::printf("%s: fewest 0.3 m voxels in a frame %zu, at %.1f s of %.1f s\n", world_name.c_str(), fewest, at, end);
  return fewest;
}

TEST(IndoorVisibility, MultilevelPathIsNeverBlind) { EXPECT_GT(fewestVoxelsAlongThePath("multilevel"), 500u); }

TEST(IndoorVisibility, CorridorPathIsNeverBlind) { EXPECT_GT(fewestVoxelsAlongThePath("corridor"), 500u); }

}  // namespace
}  // namespace uampc::raycaster
