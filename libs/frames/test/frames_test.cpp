#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "uampc/frames/detail/ray_rotation.hpp"
#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/frames/pose_knots.hpp"
#include "uampc/simd/dispatch.hpp"

namespace uampc::frames {
namespace {

TEST(MotorizedLidar, ReferenceRigTiltsLidarZTowardsMinusY) {
  // Rotating about +x by 30 degrees takes the LiDAR z axis to (0, -sin30, cos30).
  const auto c = MotorLidarCalibration::referenceRig();
  const Eigen::Vector3d z = c.R_ML * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(z.x(), 0.0, 1e-12);
  EXPECT_NEAR(z.y(), -0.5, 1e-12);
  EXPECT_NEAR(z.z(), std::sqrt(3.0) / 2.0, 1e-12);
}

TEST(MotorizedLidar, Eq1ComposesMotorCalibrationAndBasePose) {
  MotorLidarCalibration c;
  c.r_ML = Eigen::Vector3d(0.1, 0, 0);
  Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
  T_WB.translation() = Eigen::Vector3d(10, 20, 30);
  // A point 1 m ahead on the LiDAR x axis, motor at 90 degrees: it ends up on the base +y axis.
  const Eigen::Vector3d p_W = lidarToWorld(Eigen::Vector3d(1, 0, 0), M_PI / 2, c, T_WB);
  EXPECT_TRUE(p_W.isApprox(Eigen::Vector3d(10, 21.1, 30), 1e-12)) << p_W.transpose();
  const Eigen::Isometry3d T_BL = lidarPoseInBase(M_PI / 2, c);
  EXPECT_TRUE((T_BL * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(0, 1.1, 0), 1e-12));
}

TEST(MotorizedLidar, RotorReadingTakesOutTheEncoderZeroAndTheClockOffset) {
  MotorLidarCalibration c;
  const MotorReading encoder{10.0, 2.0, 3.6};
  const MotorReading same = rotorReading(encoder, c);  // zero offsets: the reading bit for bit
  EXPECT_EQ(std::memcmp(&same, &encoder, sizeof(MotorReading)), 0);
  c.encoder_offset = 0.25;  // the encoder reads theta + 0.25
  c.time_offset = 0.004;    // a point stamped t was measured when the encoder's clock read t + 4 ms
  const MotorReading rotor = rotorReading(encoder, c);
  EXPECT_DOUBLE_EQ(rotor.theta, 1.75);
  EXPECT_DOUBLE_EQ(rotor.time, 9.996);
  EXPECT_DOUBLE_EQ(rotor.omega, 3.6);
}

TEST(MotorizedLidar, RollPitchYawIsZyxAboutFixedAxesAndRoundTrips) {
  const Eigen::Vector3d rpy(0.3, -0.2, 1.1);
  const Eigen::Matrix3d R = rotationFromRollPitchYaw(rpy);
  const Eigen::Matrix3d expected =
      (Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  EXPECT_TRUE(R.isApprox(expected, 1e-14));
  EXPECT_TRUE(rollPitchYawFromRotation(R).isApprox(rpy, 1e-12));
  // A roll alone is the reference rig's tilt about x.
  EXPECT_TRUE(rotationFromRollPitchYaw({M_PI / 6, 0, 0}).isApprox(MotorLidarCalibration::referenceRig().R_ML, 1e-15));
}

TEST(MotorizedLidar, MountingErrorTurnsInTheLidarFrameAndShiftsInTheMotorFrame) {
  const auto believed = MotorLidarCalibration::referenceRig();
  MountingError error;
  error.rotation_rpy = {0.0, 0.0, 0.1};  // about the LiDAR's own z axis
  error.offset = {0.01, 0.0, 0.0};
  error.encoder_offset = 0.02;
  error.time_offset = 0.003;
  const auto truth = withMountingError(believed, error);
  EXPECT_TRUE(truth.R_ML.isApprox(believed.R_ML * Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()), 1e-15));
  EXPECT_TRUE(truth.r_ML.isApprox(Eigen::Vector3d(0.01, 0, 0)));
  EXPECT_DOUBLE_EQ(truth.encoder_offset, 0.02);
  EXPECT_DOUBLE_EQ(truth.time_offset, 0.003);
}

TEST(MotorAngleTrack, InterpolatesLinearlyInsideAndRefusesOutside) {
  MotorAngleTrack track;
  ASSERT_TRUE(track.add({0.0, 0.0, 1.0}));
  ASSERT_TRUE(track.add({0.1, 0.4, 4.0}));
  ASSERT_TRUE(track.add({0.2, 1.0, 6.0}));
  EXPECT_FALSE(track.add({0.2, 5.0, 0.0}));  // not newer
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.05), 0.2);
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.15), 0.7);
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.2), 1.0);
  EXPECT_DOUBLE_EQ(*track.thetaAt(0.0), 0.0);
  EXPECT_FALSE(track.thetaAt(-0.01).has_value());
  EXPECT_FALSE(track.thetaAt(0.21).has_value());
  EXPECT_TRUE(track.covers(0.0, 0.2));
  EXPECT_FALSE(track.covers(0.0, 0.25));
}

TEST(MotorAngleTrack, DropsReadingsOlderThanTheWindow) {
  MotorAngleTrack track(1.0);
  for (int i = 0; i <= 300; ++i) track.add({i * 0.01, i * 0.036, 3.6});
  EXPECT_NEAR(track.oldest().time, 2.0, 1e-9);
  EXPECT_NEAR(track.newest().time, 3.0, 1e-9);
}


// The LiDAR of a fast rig (motor 7.2 rad/s, base turning at 1.3 rad/s and accelerating) over one
// 0.1 s frame: the knots reproduce the exact pose far below a float's precision, and ask for poses
// inside the frame only.
TEST(PoseKnots, InterpolatesAFastRigFarBelowFloatPrecision) {
  const MotorLidarCalibration calibration = MotorLidarCalibration::referenceRig();
  double asked_min = 1e9, asked_max = -1e9;
  const double t0 = 100.0, t1 = 100.0999;
  const auto exact = [&](double time) {
    asked_min = std::min(asked_min, time);
    asked_max = std::max(asked_max, time);
    const double t = time - t0 + 0.3;
    Eigen::Isometry3d T_WB = Eigen::Isometry3d::Identity();
    T_WB.linear() = (Eigen::AngleAxisd(1.3 * t + 0.8 * t * t, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(0.2 * std::sin(3.0 * t), Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    T_WB.translation() = Eigen::Vector3d(5.0 * t + 1.5 * t * t, std::sin(t), 0.1 * t);
    return T_WB * lidarPoseInBase(7.2 * t, calibration);
  };
  PoseKnots knots;
  knots.build(t0, t1, exact);
  EXPECT_EQ(knots.size(), 401u);
  EXPECT_GE(asked_min, t0);
  EXPECT_LE(asked_max, t1);
  double worst_translation = 0.0, worst_rotation = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    const double t = t0 + (t1 - t0) * i / 1000.0;
    const Eigen::Isometry3d a = knots(t), b = exact(t);
    worst_translation = std::max(worst_translation, (a.translation() - b.translation()).norm());
    worst_rotation = std::max(worst_rotation, Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle());
  }
  // ~2e-8 m and ~2e-8 rad here; a float coordinate at 40 m resolves 2.4e-6 m.
  EXPECT_LT(worst_translation, 1e-7);
  EXPECT_LT(worst_rotation, 1e-7);
  // A frame of one instant: every time gets that pose.
  knots.build(t0, t0, exact);
  EXPECT_LT((knots(t0).translation() - exact(t0).translation()).norm(), 1e-12);
}

bool sameBits(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return std::memcmp(a.data(), b.data(), sizeof(float) * 3) == 0;
}

// Random blended quaternions (not normalised, as a blend of two unit ones is) and unit directions,
// with the awkward ones: a zero quaternion and a zero direction (returned as they are), a
// quaternion far from unit length, and the axes.
detail::RayBlock awkwardRays(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  detail::RayBlock block;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector4d q = Eigen::Vector4d(coefficient(rng), coefficient(rng), coefficient(rng), coefficient(rng));
    const Eigen::Vector3d d = Eigen::Vector3d(coefficient(rng), coefficient(rng), coefficient(rng)).normalized();
    block.qx[i] = q.x();
    block.qy[i] = q.y();
    block.qz[i] = q.z();
    block.qw[i] = q.w();
    // A pattern's directions are float.
    block.dx[i] = static_cast<float>(d.x());
    block.dy[i] = static_cast<float>(d.y());
    block.dz[i] = static_cast<float>(d.z());
  }
  block.qx[0] = block.qy[0] = block.qz[0] = block.qw[0] = 0.0;
  block.dx[1] = block.dy[1] = block.dz[1] = 0.0;
  block.qx[2] *= 1e3;
  block.qw[2] *= 1e3;
  block.dx[3] = 1.0;
  block.dy[3] = block.dz[3] = 0.0;
  return block;
}

// The vectorised ray rotation gives, bit for bit, what Eigen gives: normalised(float(
// q.normalized() * d)) (the raycaster's rays were computed so before the loop was vectorised, and
// lockstep runs keep their outputs), in both builds (the AVX2 one where the CPU has it).
TEST(RayRotation, IsEigensBitForBitInBothBuilds) {
  std::mt19937 rng(3);
  const int n = detail::RayBlock::kSize - 3;  // not a multiple of a vector's width
  for (int round = 0; round < 20; ++round) {
    detail::RayBlock baseline = awkwardRays(rng, n);
    detail::RayBlock avx2 = baseline;
    const detail::RayBlock in = baseline;
    detail::builds::rotateRaysBaseline(n, baseline);
    if (simd::cpuHasAvx2()) detail::builds::rotateRaysAvx2(n, avx2);
    for (int i = 0; i < n; ++i) {
      const Eigen::Quaterniond q(in.qw[i], in.qx[i], in.qy[i], in.qz[i]);
      const Eigen::Vector3d d(in.dx[i], in.dy[i], in.dz[i]);
      const Eigen::Vector3f expected = (q.normalized() * d).cast<float>().normalized();
      const Eigen::Vector3f got(baseline.ux[i], baseline.uy[i], baseline.uz[i]);
      ASSERT_TRUE(sameBits(got, expected)) << "ray " << i << ": " << got.transpose() << " against "
                                            << expected.transpose();
      if (simd::cpuHasAvx2()) {
        ASSERT_TRUE(sameBits(Eigen::Vector3f(avx2.ux[i], avx2.uy[i], avx2.uz[i]), expected)) << "AVX2, ray " << i;
      }
    }
  }
}

// placeRays: each ray's origin is the knots' position at its time (the same bits), and its
// direction the knots' rotation of it; over several blocks and a partial one, times before, within
// and after the knots.
TEST(PoseKnots, PlacesEveryRayWithThePoseAtItsTime) {
  const auto pose = [](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(7.2 * t, Eigen::Vector3d(0.3, -0.5, 1.0).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(-40.0 + 5.0 * t, 2.0 * t * t, 1.5);
    return T;
  };
  PoseKnots knots;
  knots.build(0.0, 0.0999, pose);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> time(-0.01, 0.11);
  std::uniform_real_distribution<float> coordinate(-1.0F, 1.0F);
  const std::size_t n = 3 * detail::RayBlock::kSize + 17;
  std::vector<double> times(n);
  std::vector<Eigen::Vector3f> directions(n);
  for (std::size_t k = 0; k < n; ++k) {
    times[k] = time(rng);
    directions[k] = Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
  }
  std::vector<int> written(n, 0);
  knots.placeRays(
      n, [&](std::size_t k) { return times[k]; }, [&](std::size_t k) { return directions[k]; },
      [&](std::size_t k, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
        ASSERT_LT(k, n);
        ++written[k];
        const Eigen::Isometry3d T = knots(times[k]);
        EXPECT_TRUE(sameBits(origin, T.translation().cast<float>())) << "ray " << k;
        const Eigen::Vector3f expected = (T.linear() * directions[k].cast<double>()).cast<float>();
        EXPECT_LT((direction - expected).norm(), 1e-6F) << "ray " << k;
        EXPECT_NEAR(direction.norm(), 1.0F, 1e-6F);
      });
  EXPECT_EQ(std::count(written.begin(), written.end(), 1), static_cast<long>(n));  // each once
}

}  // namespace
}  // namespace uampc::frames
