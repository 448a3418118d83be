// TF end to end: a viewer that knows only the recorded /tf and /tf_static places the recorded
// /lidar/points (frame lidar) on the world's surfaces. Each point goes through the ground-truth
// chain map -> ground_truth (the true base_link) -> motor -> rotor -> lidar, every dynamic edge
// interpolated at the point's own time (stamp + t) as tf2 does (linear in translation, slerp in
// rotation), and is compared with the world the scene's map_provider builds: a ray cast from the
// LiDAR origin along the point's direction must meet a surface at the point's range.
//
// The bound: the scene's range noise is Gaussian, sigma 2 cm (the Mid-360 datasheet, the
// raycaster's default), and the residual along the ray is exactly that noise when the chain is
// right, so |residual| has median 0.674 sigma = 1.3 cm and 99th percentile 2.576 sigma = 5.2 cm.
// We require median < 3 cm and 99th percentile < 10 cm. The residual along the ray bounds the
// distance to the nearest surface from above (the surface point it meets is one such point), so
// passing it proves the points lie on surfaces. The same check fails with the static transform
// tilted 5 degrees more and with the motor angle taken at the frame's stamp instead of each point's
// time, so it can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/raycaster/ray_cast_scene.hpp"
#include "uampc/run_files/csv.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::test {
namespace {

struct StampedTransform {
  double stamp;
  Eigen::Vector3d translation;
  Eigen::Quaterniond rotation;
};

// The samples of one TF edge (parent -> child) as the CSV recorder wrote them.
class RecordedEdge {
 public:
  explicit RecordedEdge(const std::string& path) {
    const run_files::CsvTable table = run_files::readCsv(path);
    for (const auto& r : table.rows) {
      samples_.push_back(
          {r.at(0), {r.at(1), r.at(2), r.at(3)}, Eigen::Quaterniond(r.at(7), r.at(4), r.at(5), r.at(6))});
    }
  }
  std::size_t size() const { return samples_.size(); }
  Eigen::Isometry3d only() const {
    EXPECT_EQ(samples_.size(), 1u);
    return isometry(samples_.at(0).translation, samples_.at(0).rotation);
  }
  // tf2's lookup at time t: between the two samples around t; none outside the recorded span.
  std::optional<Eigen::Isometry3d> at(double t) const {
    auto after = std::lower_bound(samples_.begin(), samples_.end(), t,
                                  [](const StampedTransform& s, double time) { return s.stamp < time; });
    if (after == samples_.end()) return std::nullopt;
    if (after->stamp == t) return isometry(after->translation, after->rotation);
    if (after == samples_.begin()) return std::nullopt;
    const StampedTransform& before = *(after - 1);
    const double a = (t - before.stamp) / (after->stamp - before.stamp);
    return isometry((1 - a) * before.translation + a * after->translation, before.rotation.slerp(a, after->rotation));
  }

 private:
  static Eigen::Isometry3d isometry(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = t;
    return T;
  }
  std::vector<StampedTransform> samples_;
};

struct RecordedPoint {
  double stamp;
  double time;  // stamp + the point's t
  Eigen::Vector3d p_L;
};

// Which times the motor -> rotor edge is looked up at: each point's own, or its frame's stamp.
enum class MotorLookup { kPointTime, kFrameStamp };

struct Residuals {
  std::vector<double> values;  // m, |range - distance to the surface met|, infinity for no surface
  double quantile(double q) const {
    std::vector<double> v = values;
    const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + k, v.end());
    return v[static_cast<std::size_t>(k)];
  }
  double shareAbove(double bound) const {
    const auto n = std::count_if(values.begin(), values.end(), [bound](double v) { return v > bound; });
    return static_cast<double>(n) / static_cast<double>(values.size());
  }
  std::string summary() const {
    char text[160];
    std::snprintf(text, sizeof text, "median %.4f m, 99th percentile %.4f m, %.2f %% beyond 10 cm (no surface: inf)",
                  quantile(0.5), quantile(0.99), 100.0 * shareAbove(0.10));
    return text;
  }
};

class RecordedRun {
 public:
  explicit RecordedRun(const std::string& out)
      : ground_truth_(out + "/recorder_tf_map_to_ground_truth.csv"),
        motor_(out + "/recorder_tf_motor_to_rotor.csv"),
        base_motor_(RecordedEdge(out + "/recorder_tf_static_base_link_to_motor.csv").only()),
        rotor_lidar_(RecordedEdge(out + "/recorder_tf_static_rotor_to_lidar.csv").only()) {
    for (const auto& r : run_files::readCsv(out + "/recorder_scans.csv").rows) {
      points_.push_back({r.at(0), r.at(0) + r.at(5), {r.at(1), r.at(2), r.at(3)}});
    }
  }

  const std::vector<RecordedPoint>& points() const { return points_; }
  const Eigen::Isometry3d& rotorToLidar() const { return rotor_lidar_; }
  std::size_t motorSamples() const { return motor_.size(); }
  std::size_t groundTruthSamples() const { return ground_truth_.size(); }

  // Every point placed in map through the chain, with rotor -> lidar as given, and its residual.
  Residuals residuals(const raycaster::RayCastScene& world, const Eigen::Isometry3d& rotor_lidar,
                      MotorLookup lookup) const {
    Residuals r;
    for (const RecordedPoint& point : points_) {
      const auto T_map_base = ground_truth_.at(point.time);
      const auto T_motor_rotor = motor_.at(lookup == MotorLookup::kPointTime ? point.time : point.stamp);
      EXPECT_TRUE(T_map_base && T_motor_rotor) << "no transform recorded around t=" << point.time;
      if (!T_map_base || !T_motor_rotor) return r;
      const Eigen::Isometry3d T_map_lidar = *T_map_base * base_motor_ * *T_motor_rotor * rotor_lidar;
      r.values.push_back(residual(world, T_map_lidar.translation(), T_map_lidar * point.p_L));
    }
    return r;
  }

 private:
  static double residual(const raycaster::RayCastScene& world, const Eigen::Vector3d& origin,
                         const Eigen::Vector3d& point) {
    const double range = (point - origin).norm();
    const raycaster::Ray ray{origin.cast<float>(), ((point - origin) / range).cast<float>(),
                             static_cast<float>(range + 1.0)};
    const raycaster::Hit hit = world.intersect(ray);
    return hit.valid ? std::abs(range - hit.distance) : std::numeric_limits<double>::infinity();
  }

  RecordedEdge ground_truth_;
  RecordedEdge motor_;
  Eigen::Isometry3d base_motor_;
  Eigen::Isometry3d rotor_lidar_;
  std::vector<RecordedPoint> points_;
};

// The world tests/scenes/tf_campus.yaml's map_provider builds: the campus, seed 1.
raycaster::RayCastScene campusWorld() {
  world::WorldSettings settings;
  settings.world = "campus";
  settings.seed = 1;
  const world::World world = world::buildWorld(settings);
  return raycaster::RayCastScene(world.mesh, world.points);
}

TEST(Tf, RecordedScansPlacedThroughRecordedTfLandOnTheWorldsSurfaces) {
  const std::string out = freshDirectory("tf_campus");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/tf_campus.yaml") + " --out " + out +
                                   domainOverride(DomainBlock::kTf, 0));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const RecordedRun run(out);
  std::set<double> stamps;
  for (const RecordedPoint& p : run.points()) stamps.insert(p.stamp);
  ASSERT_EQ(stamps.size(), 5u);  // frames 20-24: the motor at speed
  EXPECT_NEAR(*stamps.begin(), 2.0, 1e-9);
  ASSERT_GT(run.points().size(), 5u * 5000u);
  EXPECT_GT(run.motorSamples(), 500u);  // 200 Hz over 3.5 s
  EXPECT_GT(run.groundTruthSamples(), 500u);
  const raycaster::RayCastScene world = campusWorld();

  const Residuals right = run.residuals(world, run.rotorToLidar(), MotorLookup::kPointTime);
  ASSERT_EQ(right.values.size(), run.points().size());
  const double median = right.quantile(0.5), p99 = right.quantile(0.99);
  std::printf("TF chain as recorded, %zu points: %s; max %.4f m\n", right.values.size(), right.summary().c_str(),
              right.quantile(1.0));
  EXPECT_LT(median, 0.03);
  EXPECT_LT(p99, 0.10);

  // The check can fail: the LiDAR tilted 5 degrees more than the rig says...
  const Eigen::Isometry3d tilted = run.rotorToLidar() * Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitX());
  const Residuals wrong_tilt = run.residuals(world, tilted, MotorLookup::kPointTime);
  std::printf("tilt + 5 degrees: %s\n", wrong_tilt.summary().c_str());
  EXPECT_TRUE(wrong_tilt.quantile(0.5) >= 0.03 || wrong_tilt.quantile(0.99) >= 0.10);
  // ... or the motor's angle at the frame's start for every point (no per-point interpolation).
  const Residuals frame_stamp = run.residuals(world, run.rotorToLidar(), MotorLookup::kFrameStamp);
  std::printf("motor angle at the frame stamp: %s\n", frame_stamp.summary().c_str());
  EXPECT_TRUE(frame_stamp.quantile(0.5) >= 0.03 || frame_stamp.quantile(0.99) >= 0.10);
}

}  // namespace
}  // namespace uampc::test
