#include "uampc/raycaster/ray_caster.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "uampc/frames/motorized_lidar.hpp"

namespace uampc::raycaster {
namespace {

using frames::MotorAngleTrack;
using frames::MotorLidarCalibration;

world::TriangleMesh groundPlane(float half = 200.0f) {
  world::TriangleMesh mesh;
  mesh.addGroundRectangle(-half, -half, half, half, 0.0f);
  return mesh;
}

// A base that moves and turns during the frame, and a motor turning at 3.6 rad/s.
Eigen::Isometry3d movingBase(double t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(1.5 * t, 0.3 * t, 2.0 + 0.1 * t);
  T.linear() =
      (Eigen::AngleAxisd(0.4 * t, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return T;
}
double spinningMotor(double t) { return 0.3 + 3.6 * t; }

world::Trajectory movingTrajectory(double t0, double t1) {
  std::vector<world::TimedPose> poses;
  for (double t = t0; t <= t1 + 1e-9; t += 0.01) {
    const Eigen::Isometry3d T = movingBase(t);
    poses.push_back({t, T.translation(), Eigen::Quaterniond(T.linear())});
  }
  return world::Trajectory(poses);
}

MotorAngleTrack motorTrack(double t0, double t1) {
  MotorAngleTrack track(100.0);
  for (double t = t0; t <= t1 + 1e-9; t += 0.005) track.add({t, spinningMotor(t), 3.6});
  return track;
}

// Expected range along the ray of a scan point, in double precision, to the planes of an
// axis-aligned box room [lo, hi] seen from inside (or to z = 0 when there is no room).
double expectedRangeInBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
                          const Eigen::Vector3d& hi) {
  double best = 1e30;
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(d[axis]) < 1e-12) continue;
    const double wall = d[axis] > 0 ? hi[axis] : lo[axis];
    best = std::min(best, (wall - o[axis]) / d[axis]);
  }
  return best;
}

TEST(RayCaster, PlaneRangesAreExactAndDerotatedPointsLandOnThePlane) {
  RayCaster caster(groundPlane(), RayCasterConfig{});
  const double start = 100.0;
  const Scan scan = caster.castFrame(0, start, movingBase, spinningMotor);
  ASSERT_GT(scan.points.size(), 1000u);
  const auto calibration = MotorLidarCalibration::referenceRig();
  for (const auto& p : scan.points) {
    const double t = start + p.time_offset;
    const Eigen::Vector3d p_W =
        frames::lidarToWorld(p.position.cast<double>(), spinningMotor(t), calibration, movingBase(t));
    ASSERT_LT(std::abs(p_W.z()), 1e-3) << "point at t=" << p.time_offset;
    // Range in double precision, along the same ray.
    const Eigen::Isometry3d T_WL = movingBase(t) * frames::lidarPoseInBase(spinningMotor(t), calibration);
    const Eigen::Vector3d d = T_WL.linear() * p.position.cast<double>().normalized();
    const double range = -T_WL.translation().z() / d.z();
    ASSERT_NEAR(p.position.norm(), range, 1e-3);
    ASSERT_GE(p.intensity, 0.0f);
    ASSERT_LE(p.intensity, 255.0f);
    ASSERT_GE(p.position.norm(), 1.5f);
    ASSERT_LE(p.position.norm(), 40.0f);
  }
}

TEST(RayCaster, BoxRoomRangesAreExact) {
  const Eigen::Vector3d lo(-4, -3, 0), hi(6, 5, 3.5);
  world::TriangleMesh room;
  room.addBox(lo.cast<float>(), hi.cast<float>());
  RayCasterConfig config;
  config.model = lidar::velodyneVlp16();
  RayCaster caster(room, config);
  auto base = [](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.5 * t, 0.2, 1.2);
    T.linear() = Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
  const Scan scan = caster.castFrame(0, 0.0, base, spinningMotor);
  EXPECT_EQ(scan.rays, 28800u);
  ASSERT_GT(scan.points.size(), 28000u);  // a closed room: almost every ray returns
  const auto calibration = MotorLidarCalibration::referenceRig();
  for (const auto& p : scan.points) {
    const double t = p.time_offset;
    const Eigen::Isometry3d T_WL = base(t) * frames::lidarPoseInBase(spinningMotor(t), calibration);
    const Eigen::Vector3d d = T_WL.linear() * p.position.cast<double>().normalized();
    ASSERT_NEAR(p.position.norm(), expectedRangeInBox(T_WL.translation(), d, lo, hi), 1e-3);
  }
}

// Frame 3, at 5 s, of the moving base and spinning motor, from their recorded histories.
struct RecordedFrame {
  double start = 5.0;
  world::Trajectory trajectory = movingTrajectory(4.9, 5.2);
  MotorAngleTrack motor = motorTrack(4.9, 5.2);
  Scan castBy(RayCaster& caster) const { return caster.castFrame(3, start, trajectory, motor); }
};

TEST(RayCaster, WorksFromTrajectoryAndEncoderTrackAndTheMotorTurnsDuringTheFrame) {
  RayCaster caster(groundPlane(), RayCasterConfig{});
  const RecordedFrame frame;
  const auto& [start, trajectory, motor] = std::tie(frame.start, frame.trajectory, frame.motor);
  const Scan scan = frame.castBy(caster);
  ASSERT_GT(scan.points.size(), 1000u);
  const auto calibration = MotorLidarCalibration::referenceRig();
  double worst_frozen = 0.0;
  for (const auto& p : scan.points) {
    const double t = start + p.time_offset;
    const Eigen::Vector3d p_W =
        frames::lidarToWorld(p.position.cast<double>(), *motor.thetaAt(t), calibration, trajectory.poseAt(t));
    ASSERT_LT(std::abs(p_W.z()), 1e-3);
    // De-rotating with the angle at the frame start instead is wrong: the motor moved.
    const Eigen::Vector3d frozen =
        frames::lidarToWorld(p.position.cast<double>(), *motor.thetaAt(start), calibration, trajectory.poseAt(t));
    worst_frozen = std::max(worst_frozen, std::abs(frozen.z()));
  }
  EXPECT_GT(worst_frozen, 0.1);
  EXPECT_THROW(caster.castFrame(0, 5.15, trajectory, motor), std::out_of_range);
  EXPECT_THROW(caster.castFrame(0, 4.85, trajectory, motor), std::out_of_range);
}

// Snapshot frames (the reference simulator's): every point at offset 0, cast from the pose at the
// frame's stamp, so that placing them with the stamp's pose alone lands them on the plane, and
// with each continuous-frame point's own time would not. The same rays as a continuous frame of a
// rig that stands still.
TEST(RayCaster, SnapshotFramesCastEveryRayFromThePoseAtTheStamp) {
  RayCasterConfig config;
  config.frame_timing = FrameTiming::kSnapshot;
  RayCaster caster(groundPlane(), config);
  const RecordedFrame frame;
  const auto& [start, trajectory, motor] = std::tie(frame.start, frame.trajectory, frame.motor);
  const Scan scan = frame.castBy(caster);
  ASSERT_GT(scan.points.size(), 1000u);
  const auto calibration = MotorLidarCalibration::referenceRig();
  for (const auto& p : scan.points) {
    ASSERT_EQ(p.time_offset, 0.0f);
    const Eigen::Vector3d p_W =
        frames::lidarToWorld(p.position.cast<double>(), *motor.thetaAt(start), calibration, trajectory.poseAt(start));
    ASSERT_LT(std::abs(p_W.z()), 1e-3);
  }
  // It needs the trajectory and the encoder at the stamp only, not over the frame.
  const world::Trajectory short_trajectory = movingTrajectory(4.9, 5.02);
  const MotorAngleTrack short_motor = motorTrack(4.9, 5.02);
  EXPECT_NO_THROW(caster.castFrame(4, start, short_trajectory, short_motor));

  // A rig standing still: a snapshot is the continuous frame with its offsets dropped.
  auto still = [](double) { return movingBase(0.0); };
  auto stopped = [](double) { return 0.7; };
  RayCaster continuous(groundPlane(), RayCasterConfig{});
  const Scan a = caster.castFrame(0, 0.0, still, stopped), b = continuous.castFrame(0, 0.0, still, stopped);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t k = 0; k < a.points.size(); ++k) ASSERT_LT((a.points[k].position - b.points[k].position).norm(), 1e-4);
}

TEST(RayCaster, RangeLimits) {
  // The plane 50 m below: beyond max_range, nothing returns.
  auto high = [](double) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().z() = 50.0;
    return T;
  };
  RayCaster caster(groundPlane(), RayCasterConfig{});
  EXPECT_TRUE(caster.castFrame(0, 0.0, high, spinningMotor).points.empty());
  // A small box around the sensor, closer than min_range, hides the plane: nothing returns.
  world::TriangleMesh boxed = groundPlane();
  boxed.addBox({-0.5f, -0.5f, 1.5f}, {0.5f, 0.5f, 2.5f});
  auto at2m = [](double) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().z() = 2.0;
    return T;
  };
  RayCaster boxed_caster(boxed, RayCasterConfig{});
  EXPECT_TRUE(boxed_caster.castFrame(0, 0.0, at2m, spinningMotor).points.empty());
}

TEST(RayCaster, NoiseAndDropoutAreSeededAndHaveTheRightSize) {
  RayCasterConfig clean_config;
  RayCaster clean(groundPlane(), clean_config);
  RayCasterConfig config;
  config.range_noise_stddev = 0.02;
  config.seed = 4;
  RayCaster noisy(groundPlane(), config);
  const Scan a = clean.castFrame(2, 0.0, movingBase, spinningMotor);
  const Scan b = noisy.castFrame(2, 0.0, movingBase, spinningMotor);
  const Scan b2 = noisy.castFrame(2, 0.0, movingBase, spinningMotor);
  ASSERT_EQ(a.points.size(), b.points.size());
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_EQ(b.points[i].position, b2.points[i].position);
    const double e = b.points[i].position.norm() - a.points[i].position.norm();
    sum += e;
    sum2 += e * e;
  }
  const double n = static_cast<double>(a.points.size());
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.02, 0.002);

  config.seed = 5;
  RayCaster other(groundPlane(), config);
  EXPECT_NE(other.castFrame(2, 0.0, movingBase, spinningMotor).points[0].position, b.points[0].position);

  RayCasterConfig lossy_config;
  lossy_config.dropout_probability = 0.3;
  RayCaster lossy(groundPlane(), lossy_config);
  const double kept = static_cast<double>(lossy.castFrame(2, 0.0, movingBase, spinningMotor).points.size()) / n;
  EXPECT_NEAR(kept, 0.7, 0.02);
}

TEST(RayCaster, AngularNoiseTurnsTheReportedDirectionNotTheRange) {
  RayCaster clean(groundPlane(), RayCasterConfig{});
  RayCasterConfig config;
  config.angular_noise_stddev = 0.15 * M_PI / 180.0;  // the Mid-360 datasheet
  config.seed = 4;
  RayCaster blurred(groundPlane(), config);
  const Scan a = clean.castFrame(2, 0.0, movingBase, spinningMotor);
  const Scan b = blurred.castFrame(2, 0.0, movingBase, spinningMotor);
  ASSERT_EQ(a.points.size(), b.points.size());
  double sum2 = 0.0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const Eigen::Vector3f& p = a.points[i].position;
    const Eigen::Vector3f& q = b.points[i].position;
    EXPECT_NEAR(q.norm(), p.norm(), 1e-4f * p.norm());  // same range
    const double angle = std::atan2(double(p.cross(q).norm()), double(p.dot(q)));
    sum2 += angle * angle;
  }
  // Two axes of sigma each: the angle between cast and reported direction has RMS sqrt(2) sigma.
  const double rms = std::sqrt(sum2 / double(a.points.size()));
  EXPECT_NEAR(rms, std::sqrt(2.0) * config.angular_noise_stddev, 0.05 * config.angular_noise_stddev);
  config.angular_noise_stddev = -1.0;
  EXPECT_THROW(RayCaster(groundPlane(), config), std::invalid_argument);
}

TEST(LidarModel, DatasheetPrecisionOfTheMid360) {
  EXPECT_DOUBLE_EQ(lidar::livoxMid360().range_precision, 0.02);
  EXPECT_DOUBLE_EQ(lidar::livoxMid360().angular_precision_deg, 0.15);
}

TEST(RayCaster, PacketsAndSingleRaysAgree) {
  world::TriangleMesh mesh = groundPlane();
  mesh.addBox({5, -2, 0}, {7, 2, 3});
  mesh.addCylinder({-4, 3, 0}, 0.5f, 4.0f, 12);
  RayCasterConfig config;
  RayCaster packets(mesh, config);
  config.use_packets = false;
  RayCaster single(mesh, config);
  const Scan a = packets.castFrame(1, 0.0, movingBase, spinningMotor);
  const Scan b = single.castFrame(1, 0.0, movingBase, spinningMotor);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    ASSERT_LT((a.points[i].position - b.points[i].position).norm(), 1e-4f);
  }
}

// Grouping a frame's rays by laser for Embree's packets (packetOrder) only changes the order in
// which rays are traced: every ray's hit is the same, bit for bit, as in firing order.
TEST(RayCastScene, PacketOrderDoesNotChangeAnyHit) {
  world::TriangleMesh mesh = groundPlane();
  mesh.addBox({5, -2, 0}, {7, 2, 3});
  mesh.addBox({-3, -6, 0}, {3, -5, 4});
  mesh.addCylinder({-4, 3, 0}, 0.5f, 4.0f, 12);
  const RayCastScene scene(mesh);
  for (const lidar::LidarModel& model : {lidar::livoxMid360(), lidar::livoxAvia(), lidar::velodyneVlp16()}) {
    const std::vector<PatternPoint> pattern = scanPattern(model, 3);
    std::vector<Ray> rays;
    for (const PatternPoint& p : pattern) {
      const Eigen::Isometry3d T = movingBase(p.time_offset);
      rays.push_back({T.translation().cast<float>(), (T.linear() * p.direction.cast<double>()).cast<float>(), 40.0f});
    }
    const std::vector<std::uint32_t> order = packetOrder(pattern);
    ASSERT_EQ(order.size(), pattern.size());
    ASSERT_NE(order[1], 1u) << model.name << ": the order groups nothing";
    std::vector<Hit> in_firing_order, grouped;
    scene.intersect(rays, in_firing_order);
    scene.intersect(rays, grouped, order);
    std::size_t hits = 0;
    for (std::size_t k = 0; k < rays.size(); ++k) {
      ASSERT_EQ(in_firing_order[k].valid, grouped[k].valid) << model.name << " ray " << k;
      ASSERT_EQ(in_firing_order[k].distance, grouped[k].distance) << model.name << " ray " << k;
      ASSERT_EQ(in_firing_order[k].normal, grouped[k].normal) << model.name << " ray " << k;
      hits += grouped[k].valid;
    }
    EXPECT_GT(hits, rays.size() / 10) << model.name;  // the comparison saw hits on every object
  }
  std::vector<Hit> hits;
  EXPECT_THROW(scene.intersect(std::vector<Ray>(3, Ray{}), hits, {0, 1}), std::invalid_argument);
}

TEST(RayCaster, PacketOrderGroupsEachLasersShotsInWindows) {
  constexpr std::size_t kPacket = RayCastScene::kPacketSize;
  std::vector<PatternPoint> points(2 * kPacket * 3 + 5);
  for (std::size_t k = 0; k < points.size(); ++k) points[k].ring = static_cast<std::uint16_t>(k % 3);
  const std::vector<std::uint32_t> order = packetOrder(points);
  ASSERT_EQ(order.size(), points.size());
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], k);  // a permutation
  // The first packet: laser 0's first kPacket shots, in firing order; the next: laser 1's.
  for (std::size_t j = 0; j < kPacket; ++j) EXPECT_EQ(order[j], 3 * j);
  for (std::size_t j = 0; j < kPacket; ++j) EXPECT_EQ(order[kPacket + j], 3 * j + 1);
  // The second window starts after the first's 3 * kPacket shots.
  EXPECT_EQ(order[3 * kPacket], 3 * kPacket);
}

TEST(RayCaster, PointMapsAreHitAsSplatsAroundTheirPoints) {
  std::vector<Eigen::Vector3f> points;
  for (int i = -300; i <= 300; ++i) {
    for (int j = -300; j <= 300; ++j) points.emplace_back(0.05f * i, 0.05f * j, 0.0f);
  }
  RayCasterConfig config;
  config.point_radius = 0.04f;
  RayCaster caster(world::TriangleMesh{}, points, config);
  auto base = [](double) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().z() = 1.0;
    return T;
  };
  const Scan scan = caster.castFrame(0, 0.0, base, [](double) { return 0.0; });
  ASSERT_GT(scan.points.size(), 100u);
  const auto calibration = MotorLidarCalibration::referenceRig();
  for (const auto& p : scan.points) {
    const Eigen::Vector3d p_W = frames::lidarToWorld(p.position.cast<double>(), 0.0, calibration, base(0.0));
    // A splat faces the ray, so it reaches up to its radius on either side of the plane.
    ASSERT_LT(std::abs(p_W.z()), 0.04 + 1e-3);
  }
}

// A splat is hit at its point's own depth along the ray, wherever the ray crosses it, and only
// within its radius of the point.
TEST(RayCastScene, SplatsFaceTheRayAtTheirPointsDepth) {
  const RayCastScene scene(world::TriangleMesh{}, {Eigen::Vector3f(5.0f, 0.0f, 0.0f)}, 0.2f);
  for (float offset : {0.0f, 0.1f, 0.19f}) {
    Ray ray{Eigen::Vector3f::Zero(), Eigen::Vector3f(5.0f, offset, 0.0f).normalized(), 100.0f};
    const Hit hit = scene.intersect(ray);
    ASSERT_TRUE(hit.valid) << offset;
    const float depth = ray.direction.dot(Eigen::Vector3f(5.0f, 0.0f, 0.0f));
    EXPECT_NEAR(hit.distance, depth, 1e-4f) << offset;
    EXPECT_NEAR(hit.normal.dot(-ray.direction), 1.0f, 1e-4f) << offset;
  }
  Ray beside{Eigen::Vector3f::Zero(), Eigen::Vector3f(5.0f, 0.21f, 0.0f).normalized(), 100.0f};
  EXPECT_FALSE(scene.intersect(beside).valid);
}

}  // namespace
}  // namespace uampc::raycaster
