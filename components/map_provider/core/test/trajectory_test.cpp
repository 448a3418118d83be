#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

#include "temp_dir.hpp"
#include "uampc/world/generated_paths.hpp"
#include "uampc/world/trajectory_io.hpp"

namespace uampc::world {
namespace {

using test::TempDir;

Trajectory twoPoses() {
  TimedPose a, b;
  a.time = 10.0;
  a.position = {0, 0, 0};
  b.time = 11.0;
  b.position = {2, 4, -6};
  b.orientation = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ());
  return Trajectory({a, b});
}

TEST(Trajectory, InterpolatesLinearlyAndBySlerpAtTheRequestedTime) {
  const Trajectory trajectory = twoPoses();
  const Eigen::Isometry3d T = trajectory.poseAt(10.25);
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(0.5, 1.0, -1.5), 1e-12));
  const Eigen::AngleAxisd aa(T.linear());
  EXPECT_NEAR(aa.angle(), 0.25, 1e-12);
  EXPECT_NEAR(aa.axis().z(), 1.0, 1e-12);
  EXPECT_TRUE(trajectory.poseAt(11.0).translation().isApprox(Eigen::Vector3d(2, 4, -6)));
  EXPECT_TRUE(trajectory.poseAt(10.0).translation().isZero());
}

TEST(Trajectory, RefusesTimesOutsideAndUnorderedPoses) {
  const Trajectory trajectory = twoPoses();
  EXPECT_THROW(trajectory.poseAt(9.999), std::out_of_range);
  EXPECT_THROW(trajectory.poseAt(11.001), std::out_of_range);
  auto poses = trajectory.poses();
  std::swap(poses[0], poses[1]);
  EXPECT_THROW(Trajectory{poses}, std::invalid_argument);
  EXPECT_THROW(Trajectory{std::vector<TimedPose>{}}, std::invalid_argument);
}

TEST(Trajectory, AttitudeModes) {
  const Eigen::Quaterniond q =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
  std::vector<TimedPose> poses(1);
  poses[0].orientation = q;
  auto yaw = poses;
  applyAttitudeMode(yaw, AttitudeMode::kYawOnly, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(yaw[0].orientation.isApprox(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())), 1e-12));
  auto identity = poses;
  applyAttitudeMode(identity, AttitudeMode::kIdentity, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(identity[0].orientation.isApprox(Eigen::Quaterniond::Identity()));
  auto corrected = poses;
  const Eigen::Quaterniond flip(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  applyAttitudeMode(corrected, AttitudeMode::kFromFile, flip);
  EXPECT_TRUE(
      corrected[0].orientation.toRotationMatrix().isApprox(q.toRotationMatrix() * flip.toRotationMatrix(), 1e-12));
}

TEST(Trajectory, AttitudeModeNames) {
  EXPECT_EQ(attitudeModeFromName("from_file"), AttitudeMode::kFromFile);
  EXPECT_EQ(attitudeModeFromName("yaw_only"), AttitudeMode::kYawOnly);
  EXPECT_EQ(attitudeModeFromName("identity"), AttitudeMode::kIdentity);
  EXPECT_THROW(attitudeModeFromName("yaw"), std::invalid_argument);
}

TEST(TrajectoryIo, TumRoundTripAndComments) {
  TempDir dir;
  const std::string path = dir.write("a.txt",
                                     "# a comment\n"
                                     "0.0 1 2 3 0 0 0 1\n"
                                     "\n"
                                     "# another\n"
                                     "0.5 2 2 3 0 0 0.7071067811865476 0.7071067811865476\n");
  const Trajectory t = readTum(path);
  ASSERT_EQ(t.poses().size(), 2u);
  EXPECT_NEAR(t.poseAt(0.25).translation().x(), 1.5, 1e-12);
  writeTum(dir.file("b.txt"), t);
  const Trajectory back = readTum(dir.file("b.txt"));
  ASSERT_EQ(back.poses().size(), 2u);
  EXPECT_EQ(back.poses()[1].time, 0.5);
  EXPECT_TRUE(back.poses()[1].orientation.isApprox(t.poses()[1].orientation, 1e-15));
}

void expectError(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception, expected one containing: " << fragment;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
        << "message: " << e.what() << "\nexpected to contain: " << fragment;
  }
}

TEST(TrajectoryIo, MalformedFilesNameFileAndLine) {
  TempDir dir;
  const std::string header = "num,t,x,y,z,qx,qy,qz,qw\n";
  const std::string good1 = "1,100.0,0,0,0,0,0,0,1\n";
  const std::string good2 = "2,100.1,0,0,0,0,0,0,1\n";
  auto mcd = [&](const std::string& name, const std::string& body) {
    const std::string path = dir.write(name, body);
    return [path] { readMcdCsv(path); };
  };
  expectError(mcd("ntu.csv", header + good1 + "2,100.1,0,0,0,0,0\n"), "ntu.csv:3: expected 9 columns, got 7");
  expectError(mcd("word.csv", header + good1 + "2,100.1,0,abc,0,0,0,0,1\n"),
              "word.csv:3: column y: 'abc' is not a number");
  expectError(mcd("nan.csv", header + "1,100.0,nan,0,0,0,0,0,1\n"), "nan.csv:2: column x");
  expectError(mcd("back.csv", header + good2 + good1), "back.csv:3: time");
  expectError(mcd("same.csv", header + good1 + good1), "same.csv:3: time");
  expectError(mcd("gap.csv", header + good1 + "2,102.0,0,0,0,0,0,0,1\n"),
              "gap.csv:3: gap of 2 s to the previous pose exceeds max_gap 1 s");
  expectError(mcd("quat.csv", header + "1,100.0,0,0,0,0,0,0,0\n"), "quat.csv:2: quaternion");
  expectError(mcd("header.csv", "t,x,y\n" + good1), "header.csv:1: expected header");
  expectError(mcd("empty.csv", ""), "empty.csv: empty trajectory file");
  expectError(mcd("only_header.csv", header), "only_header.csv: no poses");
  expectError([&] { readMcdCsv(dir.file("missing.csv")); }, "missing.csv: cannot open");
  const std::string tum = dir.write("t.txt", "0 0 0 0 0 0 0 1\n1 0 0 0 0 0 0\n");
  expectError([&] { readTum(tum); }, "t.txt:2: expected 8 columns, got 7");

  // A file without line breaks (/dev/zero read 2.1 GB deep before "no poses in file") stops at its
  // first line's budget.
  expectError([&] { readTum("/dev/zero"); }, "/dev/zero:1: line longer than 4096 bytes");
  expectError([&] { readMcdCsv(dir.write("long.csv", std::string(5000, '1'))); }, "long.csv:1: line longer");

  // A larger max_gap accepts the gap; a disabled check too.
  TrajectoryReadOptions loose;
  loose.max_gap = 5.0;
  EXPECT_NO_THROW(readMcdCsv(dir.write("gap2.csv", header + good1 + "2,102.0,0,0,0,0,0,0,1\n"), loose));
}

// A position 1e20 m out aborted the ray-caster inside Embree; positions beyond 1e6 m from the
// origin are refused when read, with file and line, in both formats (docs/user/faults.md).
TEST(TrajectoryIo, PositionsBeyondTheCoordinateBoundAreRefusedWithFileAndLine) {
  TempDir dir;
  const std::string header = "num,t,x,y,z,qx,qy,qz,qw\n";
  expectError([&] { readMcdCsv(dir.write("far.csv", header + "1,0,0,0,0,0,0,0,1\n2,0.1,0,1e20,0,0,0,0,1\n")); },
              "far.csv:3: position is 1e+20 m from the origin, beyond the 1e+06 m");
  expectError([&] { readTum(dir.write("far.tum", "# t x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n0.1 0 0 -2e6 0 0 0 1\n")); },
              "far.tum:3: position is 2e+06 m from the origin");
  // Far, but within the bound: read as before.
  EXPECT_NO_THROW(readTum(dir.write("near.tum", "0 999999 0 0 0 0 0 1\n0.1 0 0 999999 0 0 0 1\n")));
}

// The MCD trajectories copied into the repository (data/mcd).
std::string mcdData() {
  const char* source = std::getenv("UAMPC_SOURCE_DIR");
  return std::string(source ? source : ".") + "/data/mcd";
}

TEST(TrajectoryIo, ReadsTheRealMcdTrajectories) {
  const std::string dir = mcdData();
  ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
  for (const char* name : {"ntu_day01.csv", "kth_day06.csv", "tuhh_day03.csv"}) {
    SCOPED_TRACE(name);
    const std::string path = dir + "/" + name;
    std::ifstream in(path);
    std::size_t lines = 0;
    for (std::string l; std::getline(in, l);) lines += l.empty() ? 0 : 1;

    TrajectoryReadOptions options = TrajectoryReadOptions::forMcd();
    options.start_at_zero = true;
    const Trajectory t = readMcdCsv(path, options);
    EXPECT_EQ(t.poses().size(), lines - 1);
    EXPECT_EQ(t.startTime(), 0.0);
    EXPECT_GT(t.duration(), 500.0);
    // After the pi-about-x correction the base z axis points up (the platform stays upright).
    std::size_t upright = 0;
    for (const auto& p : t.poses()) upright += (p.orientation * Eigen::Vector3d::UnitZ()).z() > 0.8;
    EXPECT_GT(upright, t.poses().size() * 95 / 100);
    // Interpolation between samples stays between them.
    const double tm = 0.5 * (t.poses()[100].time + t.poses()[101].time);
    const Eigen::Vector3d mid = 0.5 * (t.poses()[100].position + t.poses()[101].position);
    EXPECT_TRUE(t.poseAt(tm).translation().isApprox(mid, 1e-9));
    // Raw attitude (no correction) is z-down.
    TrajectoryReadOptions raw;
    const Trajectory r = readMcdCsv(path, raw);
    EXPECT_LT((r.poses()[0].orientation * Eigen::Vector3d::UnitZ()).z(), -0.8);
  }
}

TEST(GeneratedPaths, ClosedLoopAtConstantSpeedFacingForward) {
  GeneratedPathConfig config;
  config.closed = true;
  config.speed = 2.0;
  const Trajectory t = pathThroughWaypoints({{0, 0, 1}, {40, 0, 1}, {40, 30, 1}, {0, 30, 1}}, config);
  const auto& p = t.poses();
  ASSERT_GT(p.size(), 500u);  // 140 m less the cut corners, at 0.2 m a sample
  for (std::size_t i = 1; i < p.size(); ++i) {
    EXPECT_NEAR((p[i].position - p[i - 1].position).norm(), 0.2, 0.01);
    const Eigen::Vector3d heading = p[i].orientation * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d travel = (p[i].position - p[i - 1].position).normalized();
    EXPECT_GT(heading.dot(travel), 0.9) << "at sample " << i;
  }
  EXPECT_LT((p.front().position - p.back().position).norm(), 0.25);
  EXPECT_THROW(pathThroughWaypoints({{0, 0, 0}}, config), std::invalid_argument);
}

// Smooth interpolation passes through every sample and keeps the velocity continuous at samples,
// where linear interpolation's velocity jumps.
// The moving average keeps a straight constant-speed path as it is and removes alternating noise.
TEST(TrajectoryMovingAverage, RemovesAlternatingNoiseAndKeepsStraightMotion) {
  std::vector<TimedPose> poses;
  for (int i = 0; i < 50; ++i) {
    const double yaw = (i % 2 ? 0.05 : -0.05);  // +-3 degrees of alternating heading noise
    poses.push_back({0.1 * i, Eigen::Vector3d(0.5 * i, 2.0, 1.0),
                     Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))});
  }
  const Trajectory averaged = movingAverage(Trajectory(poses), 0.5);
  ASSERT_EQ(averaged.poses().size(), poses.size());
  for (std::size_t i = 5; i + 5 < poses.size(); ++i) {
    const auto& p = averaged.poses()[i];
    EXPECT_TRUE(p.position.isApprox(poses[i].position, 1e-12)) << i;  // linear motion is unchanged
    // Five samples in the window: the +-0.05 rad noise averages to +-0.01 rad.
    EXPECT_LT(Eigen::AngleAxisd(p.orientation).angle(), 0.0101) << i;
  }
}

TEST(TrajectorySmooth, PassesThroughSamplesWithContinuousVelocity) {
  std::vector<TimedPose> poses;
  for (int i = 0; i < 20; ++i) {
    const double t = 0.1 * i;
    const double yaw = 0.3 * std::sin(2.0 * t) + (i % 2 ? 0.02 : -0.02);  // noisy heading
    poses.push_back({t, Eigen::Vector3d(t * 4.0, std::sin(t), 0.1 * (i % 3)),
                     Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()))});
  }
  const Trajectory linear(poses, Interpolation::kLinear);
  const Trajectory smooth(poses, Interpolation::kSmooth);
  for (const auto& p : poses) {
    EXPECT_TRUE(smooth.poseAt(p.time).translation().isApprox(p.position, 1e-9));
    EXPECT_LT(Eigen::AngleAxisd(Eigen::Quaterniond(smooth.poseAt(p.time).linear()).conjugate() * p.orientation).angle(),
              1e-9);
  }
  auto velocityJump = [](const Trajectory& tr, double t) {
    const double e = 1e-4;
    const Eigen::Vector3d before = (tr.poseAt(t).translation() - tr.poseAt(t - e).translation()) / e;
    const Eigen::Vector3d after = (tr.poseAt(t + e).translation() - tr.poseAt(t).translation()) / e;
    const Eigen::Matrix3d R0 = tr.poseAt(t - e).linear(), R1 = tr.poseAt(t).linear(), R2 = tr.poseAt(t + e).linear();
    const double w_before = Eigen::AngleAxisd(R0.transpose() * R1).angle() / e;
    const double w_after = Eigen::AngleAxisd(R1.transpose() * R2).angle() / e;
    return std::make_pair((after - before).norm(), std::abs(w_after - w_before));
  };
  double linear_worst = 0, linear_worst_turn = 0;
  for (int i = 2; i < 18; ++i) {
    const auto lin = velocityJump(linear, 0.1 * i);
    const auto smo = velocityJump(smooth, 0.1 * i);
    linear_worst = std::max(linear_worst, lin.first);
    linear_worst_turn = std::max(linear_worst_turn, lin.second);
    EXPECT_LT(smo.first, 0.01) << "t=" << 0.1 * i;
    EXPECT_LT(smo.second, 0.05) << "t=" << 0.1 * i;
  }
  // The test is not vacuous: linear interpolation of the same samples does jump.
  EXPECT_GT(linear_worst, 0.1);
  EXPECT_GT(linear_worst_turn, 0.3);
  EXPECT_EQ(interpolationFromName("smooth"), Interpolation::kSmooth);
  EXPECT_THROW(interpolationFromName("cubic"), std::invalid_argument);
}

// A held start stands still, then accelerates evenly into the trajectory's own motion and follows
// it, hold + ease / 2 later.
TEST(TrajectoryHeldStart, StandsStillThenEasesIntoThePath) {
  std::vector<TimedPose> poses;
  for (int k = 0; k <= 100; ++k) {
    TimedPose p;
    p.time = 5.0 + 0.1 * k;  // 2 m/s along x, from t = 5 s
    p.position = {2.0 * 0.1 * k, 1.0, 0.0};
    poses.push_back(p);
  }
  const Trajectory path(poses);
  const double hold = 3.0, ease = 2.0;
  const Trajectory held = withHeldStart(path, hold, ease);
  EXPECT_DOUBLE_EQ(held.startTime(), 5.0);
  for (double t : {5.0, 6.5, 8.0}) EXPECT_NEAR((held.poseAt(t).translation() - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  auto speed = [&](double t) { return (held.poseAt(t + 0.01).translation() - held.poseAt(t).translation()).norm() / 0.01; };
  EXPECT_NEAR(speed(8.0 + 0.5), 2.0 * 0.5 / ease, 0.05);  // a quarter of the way through the ease
  EXPECT_NEAR(speed(8.0 + 1.5), 2.0 * 1.5 / ease, 0.05);
  const double delay = hold + ease / 2.0;
  for (double t : {6.0, 10.0, 14.9}) {
    EXPECT_NEAR((held.poseAt(t + delay).translation() - path.poseAt(t).translation()).norm(), 0.0, 1e-9) << t;
  }
  EXPECT_DOUBLE_EQ(held.endTime(), path.endTime() + delay);
  EXPECT_EQ(withHeldStart(path, 0.0, ease).poses().size(), path.poses().size());
}

}  // namespace
}  // namespace uampc::world
