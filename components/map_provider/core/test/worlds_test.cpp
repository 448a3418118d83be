#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <tuple>

#include "uampc/world/generated_paths.hpp"
#include "uampc/world/point_sampling.hpp"
#include "uampc/world/procedural_worlds.hpp"
#include "uampc/world/seeded_random.hpp"
#include "uampc/world/trajectory_io.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::world {
namespace {

bool sameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  return a.vertices == b.vertices && a.triangles == b.triangles;
}

// Horizontal distance from p to the polyline through path (closed if asked).
double distanceToPath(const Eigen::Vector3f& p, const std::vector<Eigen::Vector3d>& path, bool closed) {
  double best = 1e30;
  const std::size_t n = path.size();
  for (std::size_t i = 0; i + (closed ? 0 : 1) < n; ++i) {
    const Eigen::Vector2d a = path[i].head<2>(), b = path[(i + 1) % n].head<2>();
    const Eigen::Vector2d q = p.head<2>().cast<double>();
    const double u = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + u * (b - a) - q).norm());
  }
  return best;
}

TEST(SeededRandom, SameSeedSameNumbersAndInRange) {
  SeededRandom a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double x = a.uniform();
    EXPECT_EQ(x, b.uniform());
    differs |= x != c.uniform();
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
  EXPECT_TRUE(differs);
  // The first raw word of mt19937_64 with its default seed 5489 is fixed by the standard's
  // algorithm.
  SeededRandom d(5489u);
  EXPECT_EQ(d.raw(), 14514284786278117030ull);
}

TEST(Campus, DeterministicFromSeedAndRichInGeometry) {
  CampusConfig config;
  const TriangleMesh a = makeCampus(config, 7), b = makeCampus(config, 7), c = makeCampus(config, 8);
  EXPECT_TRUE(sameMesh(a, b));
  EXPECT_FALSE(sameMesh(a, c));
  EXPECT_GT(a.size(), 5000u);
  const auto box = a.bounds();
  EXPECT_LT(box.min().z(), 0.01f);
  EXPECT_GT(box.max().z(), 6.0f);
  for (const auto& t : a.triangles) {
    ASSERT_GE(t.minCoeff(), 0);
    ASSERT_LT(t.maxCoeff(), static_cast<int>(a.vertices.size()));
  }
}

// Smallest horizontal distance from the trajectory to any point above the ground (z > 1 mm), via
// a grid of the points.
double clearanceOf(const Trajectory& t, const std::vector<Eigen::Vector3f>& points, double ground_z, double reach) {
  std::map<std::pair<int, int>, std::vector<Eigen::Vector2d>> grid;
  for (const auto& p : points) {
    if (std::abs(p.z() - ground_z) < 1e-3) continue;
    grid[{static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))}].push_back(
        p.head<2>().cast<double>());
  }
  double best = reach;
  const int r = static_cast<int>(std::ceil(reach));
  for (const auto& pose : t.poses()) {
    const int cx = static_cast<int>(std::floor(pose.position.x()));
    const int cy = static_cast<int>(std::floor(pose.position.y()));
    for (int i = cx - r; i <= cx + r; ++i) {
      for (int j = cy - r; j <= cy + r; ++j) {
        auto it = grid.find({i, j});
        if (it == grid.end()) continue;
        for (const auto& q : it->second) best = std::min(best, (q - pose.position.head<2>()).norm());
      }
    }
  }
  return best;
}

TEST(Campus, TheLoopStaysOnFreeStreets) {
  CampusConfig config;
  const TriangleMesh mesh = makeCampus(config, 3);
  GeneratedPathConfig path_config;
  path_config.closed = true;
  const Trajectory loop = pathThroughWaypoints(campusLoopWaypoints(config, 1.0), path_config);
  EXPECT_GT(loop.duration(), 250.0);
  EXPECT_GT(clearanceOf(loop, sampleSurface(mesh, 4.0, 1), 0.0, 6.0), 3.0);
}

TEST(Corridor, LongPlainBox) {
  CorridorConfig config;
  const TriangleMesh mesh = makeCorridor(config);
  const auto box = mesh.bounds();
  EXPECT_NEAR(box.sizes().x(), 300.4f, 1e-3f);
  for (const auto& p : sampleSurface(mesh, 0.5, 2)) {
    ASSERT_TRUE(box.contains(p));
  }
  const auto path = corridorWaypoints(config, 1.0);
  EXPECT_NEAR((path.back() - path.front()).norm(), 296.0, 1e-9);
  // Doors every 8 m: the first one (x = 8, right side) is a 1 m gap in the wall up to 2.1 m,
  // closed 0.3 m behind the wall's face by the door leaf. Surface samples show it: none on the
  // wall's face in the gap below the lintel, some on the leaf, and the plain wall elsewhere.
  config.door_spacing = 8.0;
  const TriangleMesh doors = makeCorridor(config);
  std::size_t in_gap = 0, on_leaf = 0, on_wall_beside = 0;
  for (const auto& p : sampleSurface(doors, 50.0, 3)) {
    const bool face = std::abs(p.y() + 1.5f) < 1e-3f, leaf = std::abs(p.y() + 1.8f) < 1e-3f;
    if (p.z() < 2.0f && std::abs(p.x() - 8.0f) < 0.45f) {
      in_gap += face;
      on_leaf += leaf;
    }
    if (p.z() < 2.0f && std::abs(p.x() - 12.0f) < 0.45f) on_wall_beside += face;
  }
  EXPECT_EQ(in_gap, 0u);
  EXPECT_GT(on_leaf, 20u);
  EXPECT_GT(on_wall_beside, 20u);
}

TEST(WorldSource, RejectsDoorsCloserThanTheirWidth) {
  WorldSettings settings;
  settings.world = "corridor";
  settings.corridor_door_spacing = 0.5;
  EXPECT_THROW(buildWorld(settings), std::runtime_error);
  settings.corridor_door_spacing = 8.0;
  EXPECT_GT(buildWorld(settings).mesh.size(), 0u);
}

TEST(Multilevel, StoreysAndAPathThroughThem) {
  MultilevelConfig config;
  const TriangleMesh mesh = makeMultilevel(config);
  EXPECT_NEAR(mesh.bounds().max().z(), config.floors * config.floor_height + config.slab_thickness, 1e-3);
  const auto waypoints = multilevelWaypoints(config, 1.0);
  EXPECT_NEAR(waypoints.back().z(), (config.floors - 1) * config.floor_height + 1.0, 1e-9);
  const Trajectory path = pathThroughWaypoints(waypoints, GeneratedPathConfig{});
  EXPECT_GT(path.duration(), 60.0);
}

TEST(AroundTrajectory, KeepsClearOfThePath) {
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i <= 200; ++i) path.emplace_back(i, 20.0 * std::sin(i / 30.0), 5.0);
  AroundTrajectoryConfig config;
  const TriangleMesh a = makeAroundTrajectory(path, config, 11);
  EXPECT_TRUE(sameMesh(a, makeAroundTrajectory(path, config, 11)));
  std::size_t objects = 0;
  for (const auto& p : sampleSurface(a, 1.0, 3)) {
    if (std::abs(p.z() - 4.0f) < 1e-3f) continue;  // ground: 1 m below the path
    ++objects;
    ASSERT_GT(distanceToPath(p, path, false), config.clearance - 0.05) << p.transpose();
  }
  EXPECT_GT(objects, 1000u);
}

TEST(AroundTrajectory, AroundARealMcdTrajectory) {
  const char* source = std::getenv("UAMPC_SOURCE_DIR");
  const std::string file = std::string(source ? source : ".") + "/data/mcd/ntu_day01.csv";
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  const Trajectory t = readMcdCsv(file, TrajectoryReadOptions::forMcd());
  std::vector<Eigen::Vector3d> path;
  for (const auto& p : t.poses()) path.push_back(p.position);
  AroundTrajectoryConfig config;
  const TriangleMesh mesh = makeAroundTrajectory(path, config, 1);
  EXPECT_GT(mesh.size(), 10000u);
  // Objects keep their clearance (the ground is not flat here, so test with the object layer:
  // everything sampled more than 0.5 m above the ground under the path's nearest pose).
  std::vector<Eigen::Vector3d> thinned;
  for (const auto& p : path) {
    if (thinned.empty() || (p - thinned.back()).norm() > 1.0) thinned.push_back(p);
  }
  std::vector<Eigen::Vector3f> high;
  for (const auto& p : sampleSurface(mesh, 0.5, 2)) {
    double best = 1e30, z = 0;
    for (const auto& q : thinned) {
      const double d = (q.head<2>() - p.head<2>().cast<double>()).squaredNorm();
      if (d < best) {
        best = d;
        z = q.z();
      }
    }
    if (best < 100.0 && p.z() > z - config.base_height + 0.5) high.push_back(p);
  }
  EXPECT_GT(clearanceOf(t, high, -1e9, 6.0), config.clearance - 0.05);
}

// A checksum of a mesh: vertices rounded to the millimetre (robust to the last bits of libm),
// and the triangles' indices (FNV-1a over both).
std::uint64_t meshChecksum(const TriangleMesh& mesh) {
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](std::int64_t value) {
    for (int byte = 0; byte < 8; ++byte) {
      hash ^= static_cast<std::uint64_t>(value >> (8 * byte)) & 0xffu;
      hash *= 1099511628211ull;
    }
  };
  for (const auto& v : mesh.vertices)
    for (int d = 0; d < 3; ++d) mix(std::llround(v[d] * 1000.0));
  for (const auto& t : mesh.triangles)
    for (int d = 0; d < 3; ++d) mix(t[d]);
  return hash;
}

std::vector<Eigen::Vector3d> sinePath() {
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i <= 200; ++i) path.emplace_back(i, 20.0 * std::sin(i / 30.0), 5.0);
  return path;
}

std::vector<Eigen::Vector3d> mcdPath(const std::string& name) {
  const char* source = std::getenv("UAMPC_SOURCE_DIR");
  const std::string file = std::string(source ? source : ".") + "/data/mcd/" + name;
  const Trajectory t = readMcdCsv(file, TrajectoryReadOptions::forMcd());
  std::vector<Eigen::Vector3d> path;
  for (const auto& p : t.poses()) path.push_back(p.position);
  return path;
}

AroundTrajectoryConfig withOpenFraction(double open_fraction) {
  AroundTrajectoryConfig config;
  config.density.open_fraction = open_fraction;
  return config;
}

TEST(DensityProfile, SameSeedSameWorld) {
  for (const double open : {0.4, 1.0}) {
    const TriangleMesh a = makeAroundTrajectory(sinePath(), withOpenFraction(open), 5);
    EXPECT_TRUE(sameMesh(a, makeAroundTrajectory(sinePath(), withOpenFraction(open), 5))) << open;
    EXPECT_FALSE(sameMesh(a, makeAroundTrajectory(sinePath(), withOpenFraction(open), 6))) << open;
  }
}

// The figures were taken from the world as generated before density profiles existed (commit
// 4483d18): the rich profile must leave the existing scenes exactly as they were.
TEST(DensityProfile, RichIsTheWorldBeforeProfiles) {
  EXPECT_EQ(openFractionOfProfile("rich"), 0.0);
  const TriangleMesh sine = makeAroundTrajectory(sinePath(), withOpenFraction(0.0), 11);
  EXPECT_EQ(sine.size(), 3668u);
  EXPECT_EQ(meshChecksum(sine), 12293607041605505244ull);
  const TriangleMesh ntu = makeAroundTrajectory(mcdPath("ntu_day01.csv"), withOpenFraction(0.0), 1);
  EXPECT_EQ(ntu.size(), 27542u);
  EXPECT_EQ(meshChecksum(ntu), 4424553685897329197ull);
  // And the checksum tells worlds apart: a mixed one is another world.
  const TriangleMesh mixed =
      makeAroundTrajectory(mcdPath("ntu_day01.csv"), withOpenFraction(openFractionOfProfile("mixed")), 1);
  EXPECT_NE(meshChecksum(mixed), meshChecksum(ntu));
}

// Outward normal of triangle t, or zero for a degenerate one.
Eigen::Vector3f normalOf(const TriangleMesh& mesh, const Eigen::Vector3i& t) {
  const Eigen::Vector3f n =
      (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
  return n.norm() > 1e-9f ? Eigen::Vector3f(n.normalized()) : Eigen::Vector3f::Zero();
}

// Along a straight path on x, every open stretch's furniture (long walls following the path, cars
// parked along or across it) and the flat ground have faces facing along x, y or z only; the
// buildings (random yaw) and trees (cylinders and cones) of a built-up stretch do not. With
// open_fraction 1 only the first stretch is built-up (the start is always built-up).
TEST(DensityProfile, OpenStretchesHoldOnlyTheirFurniture) {
  std::vector<Eigen::Vector3d> path;
  for (int i = 0; i <= 1200; ++i) path.emplace_back(i, 0.0, 5.0);  // ground at z = 4
  const AroundTrajectoryConfig config = withOpenFraction(1.0);
  const auto stretches = drawStretches(1200.0, config.density, 3);
  std::map<StretchKind, int> kinds;
  for (const auto& s : stretches) ++kinds[s.kind];
  ASSERT_EQ(stretches.front().kind, StretchKind::kBuiltUp);
  ASSERT_EQ(kinds[StretchKind::kBuiltUp], 1);
  ASSERT_EQ(kinds.size(), 5u) << "every open kind should appear along 1200 m";
  // Objects of the first stretch stand within clearance + band + their own size of it.
  const float open_from = static_cast<float>(stretches.front().end + config.clearance + config.band + 25.0);

  auto tiltedBeyond = [](const TriangleMesh& mesh, float x) {
    std::size_t count = 0;
    for (const auto& t : mesh.triangles) {
      const Eigen::Vector3f n = normalOf(mesh, t).cwiseAbs();
      const float x_min = std::min({mesh.vertices[t[0]].x(), mesh.vertices[t[1]].x(), mesh.vertices[t[2]].x()});
      count += n.maxCoeff() < 0.9999f && x_min > x;
    }
    return count;
  };
  const TriangleMesh rich = makeAroundTrajectory(path, withOpenFraction(0.0), 3);
  EXPECT_GT(tiltedBeyond(rich, open_from), 1000u);  // buildings and trees

  const TriangleMesh open = makeAroundTrajectory(path, config, 3);
  EXPECT_GT(tiltedBeyond(open, -1e9f), 0u);  // the first stretch's
  EXPECT_EQ(tiltedBeyond(open, open_from), 0u);
  std::size_t car_tops = 0, wall_faces = 0;
  for (const auto& t : open.triangles) {
    const Eigen::Vector3f n = normalOf(open, t);
    const float top = std::max({open.vertices[t[0]].z(), open.vertices[t[1]].z(), open.vertices[t[2]].z()});
    car_tops += std::abs(n.z()) > 0.9999f && std::abs(top - 5.5f) < 1e-3f;  // 1.5 m above the ground
    wall_faces += std::abs(n.y()) > 0.9999f && top > 6.0f;                  // taller than any car, facing the path
  }
  EXPECT_GT(car_tops, 0u);
  EXPECT_GT(wall_faces, 0u);
  for (const auto& p : sampleSurface(open, 1.0, 3)) {
    if (std::abs(p.z() - 4.0f) < 1e-3f) continue;  // ground
    ASSERT_GT(std::abs(p.y()), config.clearance - 0.05) << p.transpose();
  }
}

TEST(DensityProfile, OpenShareOfALongPathIsTheOpenFraction) {
  const double length = 60000.0;  // about a thousand stretches
  for (const double open : {0.0, 0.25, openFractionOfProfile("mixed"), openFractionOfProfile("poor"), 1.0}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      DensityProfileConfig config;
      config.open_fraction = open;
      const auto stretches = drawStretches(length, config, seed);
      double open_length = 0.0, end = 0.0;
      for (std::size_t i = 0; i < stretches.size(); ++i) {
        const PathStretch& s = stretches[i];
        ASSERT_EQ(s.begin, end);
        ASSERT_LT(s.length(), config.max_stretch);
        if (i == 0) {
          ASSERT_FALSE(s.open());  // the start is built-up
        }
        if (i + 1 < stretches.size()) {
          ASSERT_GE(s.length(), config.min_stretch);  // only the last is cut short
        }
        end = s.end;
        if (s.open()) open_length += s.length();
      }
      EXPECT_EQ(end, length);
      EXPECT_NEAR(open_length / length, open, 0.05) << "open_fraction " << open << " seed " << seed;
    }
  }
}

template <typename Error, typename F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(DensityProfile, RefusesBadProfileNamesAndFractions) {
  EXPECT_NE(
      errorOf<std::invalid_argument>([] { openFractionOfProfile("dense"); }).find("'dense' (known: rich, mixed, poor)"),
      std::string::npos);
  EXPECT_NE(errorOf<std::invalid_argument>([] {
              makeAroundTrajectory(sinePath(), withOpenFraction(1.2), 1);
            }).find("open_fraction must be between 0 and 1"),
            std::string::npos);
  WorldSettings settings;
  settings.world = "around_trajectory";
  settings.trajectory = "file";
  const char* source = std::getenv("UAMPC_SOURCE_DIR");
  settings.trajectory_file = std::string(source ? source : ".") + "/data/mcd/tuhh_day03.csv";
  settings.density_profile = "dense";
  const std::string bad_name = errorOf<std::runtime_error>([&] { buildWorld(settings); });
  EXPECT_NE(bad_name.find("density_profile: unknown density profile 'dense'"), std::string::npos) << bad_name;
  settings.density_profile = "poor";
  for (const double bad : {-0.5, 1.5}) {
    settings.open_fraction = bad;
    const std::string bad_fraction = errorOf<std::runtime_error>([&] { buildWorld(settings); });
    EXPECT_NE(bad_fraction.find("open_fraction must be between 0 and 1"), std::string::npos) << bad_fraction;
  }
  settings.open_fraction = 0.5;
  EXPECT_NE(buildWorld(settings).description.find("open fraction 0.5"), std::string::npos);
  settings.open_fraction = WorldSettings::kUseProfile;
  EXPECT_NE(buildWorld(settings).description.find("density profile poor"), std::string::npos);
}

TEST(SurfaceSampling, DensityDeterminismAndPointsOnTheSurface) {
  TriangleMesh box;
  box.addBox({0, 0, 0}, {10, 20, 5});
  EXPECT_NEAR(box.area(), 2 * (200 + 50 + 100), 1e-3);
  const auto a = sampleSurface(box, 50.0, 9);
  EXPECT_EQ(a, sampleSurface(box, 50.0, 9));
  EXPECT_NEAR(static_cast<double>(a.size()), 700 * 50.0, 700 * 50.0 * 0.02);
  for (const auto& p : a) {
    const Eigen::Vector3f lo = p, hi = Eigen::Vector3f(10, 20, 5) - p;
    ASSERT_LT(std::min(lo.minCoeff(), hi.minCoeff()), 1e-4f);
    ASSERT_GT(std::min(lo.minCoeff(), hi.minCoeff()), -1e-4f);
  }
}

TEST(VoxelDownsample, CentroidPerVoxelInFirstSeenOrder) {
  const std::vector<Eigen::Vector3f> points = {{0.1f, 0.1f, 0.1f}, {5.1f, 0, 0}, {0.3f, 0.3f, 0.3f}, {-0.1f, 0, 0}};
  const auto out = voxelDownsample(points, 1.0);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_TRUE(out[0].isApprox(Eigen::Vector3f(0.2f, 0.2f, 0.2f)));
  EXPECT_TRUE(out[1].isApprox(Eigen::Vector3f(5.1f, 0, 0)));
  EXPECT_TRUE(out[2].isApprox(Eigen::Vector3f(-0.1f, 0, 0)));
  EXPECT_EQ(voxelDownsample(points, 0.0).size(), 4u);
}

// Found by tests/fuzz/pcd: a PCD map point at 8e33 m made the voxel index overflow its integer
// (undefined; on x86 it landed in the origin's voxel and was averaged with the points there).
TEST(VoxelDownsample, PointsBeyondTheIndexRangeKeepAVoxelOfTheirOwn) {
  const std::vector<Eigen::Vector3f> points = {{0.1f, 0.1f, 0.1f}, {8.06895e33f, 0, 0}, {-1e30f, 0, 0}};
  const auto out = voxelDownsample(points, 0.5);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0], points[0]);
  EXPECT_EQ(out[1], points[1]);
  EXPECT_EQ(out[2], points[2]);
}

// A mesh as a point map: at most one point per voxel, every point on a surface, every voxel the
// surface crosses filled, the same points for the same seed.
TEST(SurfacePointMap, OnePointPerVoxelOnTheSurface) {
  TriangleMesh plane;
  plane.addGroundRectangle(0.0f, 0.0f, 20.0f, 10.0f, 0.2f);  // one layer of 0.4 m voxels
  const auto points = surfacePointMap(plane, 0.4, 7);
  EXPECT_EQ(points.size(), 50u * 25u);
  std::map<std::tuple<int, int, int>, int> voxels;
  for (const auto& p : points) {
    ASSERT_NEAR(p.z(), 0.2f, 1e-5f);
    ++voxels[{static_cast<int>(std::floor(p.x() / 0.4f)), static_cast<int>(std::floor(p.y() / 0.4f)),
              static_cast<int>(std::floor(p.z() / 0.4f))}];
  }
  EXPECT_EQ(voxels.size(), points.size());
  EXPECT_EQ(surfacePointMap(plane, 0.4, 7), points);
  EXPECT_NEAR(expectedPointMapSize(plane.area(), 0.4), 1250.0, 1e-6);
}

TEST(SurfacePointMap, WorldsBecomePointMapsWithTheReferenceSplats) {
  WorldSettings settings;
  settings.world = "corridor";
  settings.point_map_resolution = 0.4;
  const World world = buildWorld(settings);
  EXPECT_TRUE(world.mesh.empty());
  EXPECT_GT(world.points.size(), 1000u);
  EXPECT_NEAR(world.point_radius, 0.55 * std::sqrt(3.0) * 0.4, 1e-6);
  EXPECT_NE(world.description.find("point map"), std::string::npos);
  settings.splat_radius = 0.25;
  EXPECT_FLOAT_EQ(buildWorld(settings).point_radius, 0.25f);
}

// Refused before anything is built, from the surface's area: the campus at 0.1 m (12.7 million
// points, inside the parameter's bounds) took 68 s and the start timeout called it hung.
TEST(SurfacePointMap, RefusesAResolutionThatWouldMakeTooManyPoints) {
  WorldSettings settings;
  settings.world = "campus";
  settings.point_map_resolution = 0.1;
  try {
    buildWorld(settings);
    FAIL() << "a 0.1 m point map of the campus was built";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("point_map_resolution"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("would make about 14 million points"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("more than 8 million"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace uampc::world
