#include "uampc/raycaster/imu_simulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/world/trajectory.hpp"

namespace uampc::raycaster {
namespace {

using frames::MotorLidarCalibration;

constexpr double kMotorSpeed = 3.6;  // rad/s
constexpr double kGravity = 9.81;    // m/s^2

ImuSimulatorConfig noiseFree(const MotorLidarCalibration& calibration = MotorLidarCalibration::referenceRig()) {
  ImuSimulatorConfig config;
  config.calibration = calibration;
  config.noise = ImuNoiseParameters{0.0, 0.0, 0.0, 0.0};
  return config;
}

// The ground truth as the raycaster receives it: samples at 200 Hz, interpolated linearly/slerp.
template <class PoseAt>
world::Trajectory sampledTrajectory(const PoseAt& pose_at, double t0, double t1) {
  std::vector<world::TimedPose> poses;
  for (int k = 0; t0 + 0.005 * k <= t1 + 1e-9; ++k) {
    const double t = t0 + 0.005 * k;
    const Eigen::Isometry3d T = pose_at(t);
    poses.push_back({t, T.translation(), Eigen::Quaterniond(T.linear())});
  }
  return world::Trajectory(poses);
}

// Encoder readings at 200 Hz of a motor at constant speed; resolution 0 means exact angles.
frames::MotorAngleTrack encoderTrack(double t0, double t1, double resolution = 0.0) {
  frames::MotorAngleTrack track(100.0);
  for (int k = 0; t0 + 0.005 * k <= t1 + 1e-9; ++k) {
    const double t = t0 + 0.005 * k;
    const double theta = 0.3 + kMotorSpeed * t;
    track.add({t, resolution > 0.0 ? std::round(theta / resolution) * resolution : theta, kMotorSpeed});
  }
  return track;
}

ImuMotion motionFrom(const world::Trajectory& trajectory, const frames::MotorAngleTrack& motor) {
  return {[&trajectory](double t) { return trajectory.poseAt(t); },
          [&motor](double t) { return motor.thetaAt(t).value(); }, [](double) { return kMotorSpeed; }};
}

Eigen::Matrix3d rotZ(double angle) { return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

TEST(ImuSimulator, BaseAtRestMotorSpinning) {
  const MotorLidarCalibration calibration = MotorLidarCalibration::referenceRig();
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.translation() = Eigen::Vector3d(3.0, -2.0, 1.5);
  const ImuMotion motion{[&base](double) { return base; }, [](double t) { return 0.3 + kMotorSpeed * t; },
                         [](double) { return kMotorSpeed; }};
  ImuSimulator imu(noiseFree(calibration));
  // The motor axis (base z) expressed in L.
  const Eigen::Vector3d motor_axis_L = calibration.R_ML.transpose() * Eigen::Vector3d::UnitZ();
  for (std::uint64_t k = 200; k < 260; ++k) {
    const ImuSample s = imu.sample(k, motion);
    EXPECT_NEAR(s.angular_velocity.norm(), kMotorSpeed, 1e-6);
    EXPECT_LT((s.angular_velocity - kMotorSpeed * motor_axis_L).norm(), 1e-6);
    EXPECT_NEAR(s.linear_acceleration.norm(), kGravity, 1e-3);
    const Eigen::Matrix3d R_WL = (base * frames::lidarPoseInBase(0.3 + kMotorSpeed * s.time, calibration)).linear();
    EXPECT_LT((R_WL * s.linear_acceleration - Eigen::Vector3d(0, 0, kGravity)).norm(), 1e-3) << "t=" << s.time;
  }
}

// An IMU off the LiDAR's origin (the rig's imu_offset) turns with the rotor: at rest it reads
// gravity's reaction plus the centripetal acceleration of its own point, -theta_dot^2 times its
// distance from the motor axis.
TEST(ImuSimulator, AnImuOffTheLidarOriginFeelsTheRotorsCentripetalAcceleration) {
  MotorLidarCalibration calibration = MotorLidarCalibration::referenceRig();
  calibration.imu_position_L = Eigen::Vector3d(0.011, 0.02329, -0.04412);
  const Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  const ImuMotion motion{[&base](double) { return base; }, [](double t) { return 0.3 + kMotorSpeed * t; },
                         [](double) { return kMotorSpeed; }};
  ImuSimulator imu(noiseFree(calibration));
  for (std::uint64_t k = 200; k < 260; ++k) {
    const ImuSample s = imu.sample(k, motion);
    const Eigen::Isometry3d T_BL = frames::lidarPoseInBase(0.3 + kMotorSpeed * s.time, calibration);
    Eigen::Vector3d off_axis = T_BL * calibration.imu_position_L;
    off_axis.z() = 0.0;
    ASSERT_GT(off_axis.norm(), 0.01);
    const Eigen::Vector3d expected_W = Eigen::Vector3d(0, 0, kGravity) - kMotorSpeed * kMotorSpeed * off_axis;
    EXPECT_LT((T_BL.linear() * s.linear_acceleration - expected_W).norm(), 1e-3) << "t=" << s.time;
  }
}

// A base accelerating at a constant rate and turning at a constant yaw rate, played through the
// 200 Hz ground truth and encoder track, with the LiDAR origin off the motor axis.
TEST(ImuSimulator, AcceleratingAndYawingBaseMatchesAnalyticReadings) {
  const Eigen::Vector3d r_ML(0.05, 0.02, 0.1);
  const MotorLidarCalibration calibration = MotorLidarCalibration::tiltedAboutX(30.0 * M_PI / 180.0, r_ML);
  const Eigen::Vector3d p0(1.0, 2.0, 0.5), v0(1.2, -0.4, 0.1), a0(0.8, 0.3, -0.2);
  const double yaw_rate = 0.5;  // rad/s
  auto base = [&](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = p0 + v0 * t + 0.5 * a0 * t * t;
    T.linear() = rotZ(0.2 + yaw_rate * t);
    return T;
  };
  const world::Trajectory trajectory = sampledTrajectory(base, 0.0, 3.0);
  const frames::MotorAngleTrack motor = encoderTrack(0.0, 3.0);
  const ImuMotion motion = motionFrom(trajectory, motor);
  ImuSimulator imu(noiseFree(calibration));
  double worst_gyro = 0.0, worst_accel = 0.0;
  // Every sample of 2 s, and times between the ground-truth samples too.
  for (std::uint64_t k = 100; k < 500; ++k) {
    const ImuSample s = imu.sample(k, motion);
    const ImuKinematics at_sample = imuKinematics(s.time, motion, calibration);
    ASSERT_EQ(s.angular_velocity, at_sample.angular_velocity);  // no noise configured
    ASSERT_EQ(s.linear_acceleration, at_sample.specific_force);
    for (const double offset : {0.0, 0.0013, 0.0031}) {
      const double t = s.time + offset;
      const ImuKinematics reading = imuKinematics(t, motion, calibration);
      // Both rotations are about the world z axis: L turns at yaw_rate + theta_dot about it.
      const double phi = 0.2 + yaw_rate * t + 0.3 + kMotorSpeed * t;
      const double phi_dot = yaw_rate + kMotorSpeed;
      const Eigen::Matrix3d R_WL = rotZ(phi) * calibration.R_ML;
      const Eigen::Vector3d omega_L = phi_dot * R_WL.transpose() * Eigen::Vector3d::UnitZ();
      // The origin of L is p_WB + Rz(phi) r_ML: its acceleration adds -phi_dot^2 times the
      // horizontal part of the rotated offset (centripetal).
      const Eigen::Vector3d centripetal = -phi_dot * phi_dot * rotZ(phi) * Eigen::Vector3d(r_ML.x(), r_ML.y(), 0.0);
      const Eigen::Vector3d f_L = R_WL.transpose() * (a0 + centripetal + Eigen::Vector3d(0, 0, kGravity));
      worst_gyro = std::max(worst_gyro, (reading.angular_velocity - omega_L).norm());
      worst_accel = std::max(worst_accel, (reading.specific_force - f_L).norm());
    }
  }
  EXPECT_LT(worst_gyro, 1e-6);
  EXPECT_LT(worst_accel, 1e-3);
  std::printf("accelerating base: worst gyro error %.3g rad/s, worst accel error %.3g m/s^2\n", worst_gyro,
              worst_accel);
}

// The base pitching about its y axis while the motor turns about its z axis: the two rates do not
// commute, omega_L = R_BL(theta)^T omega_B + theta_dot * R_ML^T e_z.
TEST(ImuSimulator, BaseRotationAcrossTheMotorAxisComposes) {
  const MotorLidarCalibration calibration = MotorLidarCalibration::referenceRig();
  const double pitch_rate = 0.7;  // rad/s
  auto base = [&](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(pitch_rate * t, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return T;
  };
  const world::Trajectory trajectory = sampledTrajectory(base, 0.0, 2.0);
  const frames::MotorAngleTrack motor = encoderTrack(0.0, 2.0);
  const ImuMotion motion = motionFrom(trajectory, motor);
  ImuSimulator imu(noiseFree(calibration));
  double worst_gyro = 0.0, worst_accel = 0.0;
  for (std::uint64_t k = 10; k < 390; ++k) {
    const ImuSample s = imu.sample(k, motion);
    const double theta = 0.3 + kMotorSpeed * s.time;
    const Eigen::Matrix3d R_BL = frames::lidarPoseInBase(theta, calibration).linear();
    const Eigen::Vector3d omega_L = R_BL.transpose() * Eigen::Vector3d(0, pitch_rate, 0) +
                                    kMotorSpeed * calibration.R_ML.transpose() * Eigen::Vector3d::UnitZ();
    const Eigen::Matrix3d R_WL = base(s.time).linear() * R_BL;
    worst_gyro = std::max(worst_gyro, (s.angular_velocity - omega_L).norm());
    worst_accel =
        std::max(worst_accel, (s.linear_acceleration - R_WL.transpose() * Eigen::Vector3d(0, 0, kGravity)).norm());
  }
  EXPECT_LT(worst_gyro, 1e-5);
  EXPECT_LT(worst_accel, 1e-6);
  std::printf("pitching base: worst gyro error %.3g rad/s, worst accel error %.3g m/s^2\n", worst_gyro, worst_accel);
}

// A 12-bit encoder's angle steps by 1.5 mrad; the IMU takes the motor's rate from the encoder's
// velocity, so the steps reach neither the gyro nor the centripetal acceleration.
TEST(ImuSimulator, EncoderQuantisationDoesNotReachTheReadings) {
  const Eigen::Vector3d r_ML(0.1, 0.0, 0.0);
  const MotorLidarCalibration calibration = MotorLidarCalibration::tiltedAboutX(0.5, r_ML);
  const world::Trajectory trajectory = sampledTrajectory([](double) { return Eigen::Isometry3d::Identity(); }, 0, 2);
  const frames::MotorAngleTrack motor = encoderTrack(0.0, 2.0, 2.0 * M_PI / 4096.0);
  ImuSimulator imu(noiseFree(calibration));
  const Eigen::Vector3d motor_axis_L = calibration.R_ML.transpose() * Eigen::Vector3d::UnitZ();
  double worst_gyro = 0.0, worst_accel = 0.0;
  for (std::uint64_t k = 10; k < 390; ++k) {
    const ImuSample s = imu.sample(k, motionFrom(trajectory, motor));
    const double theta = 0.3 + kMotorSpeed * s.time;
    const Eigen::Matrix3d R_WL = rotZ(theta) * calibration.R_ML;
    const Eigen::Vector3d a_W = -kMotorSpeed * kMotorSpeed * rotZ(theta) * r_ML;
    worst_gyro = std::max(worst_gyro, (s.angular_velocity - kMotorSpeed * motor_axis_L).norm());
    worst_accel = std::max(worst_accel,
                           (s.linear_acceleration - R_WL.transpose() * (a_W + Eigen::Vector3d(0, 0, kGravity))).norm());
  }
  EXPECT_LT(worst_gyro, 1e-6);
  // Differentiating the encoder angle instead gives errors of ~0.1 rad/s and ~1 m/s^2.
  EXPECT_LT(worst_accel, 1e-3);
  std::printf("quantised encoder: worst gyro error %.3g rad/s, worst accel error %.3g m/s^2\n", worst_gyro,
              worst_accel);
}

ImuMotion atRest() {
  return {[](double) { return Eigen::Isometry3d::Identity(); }, [](double t) { return kMotorSpeed * t; },
          [](double) { return kMotorSpeed; }};
}

// Sample standard deviation per axis of the errors e(k) over all k.
Eigen::Vector3d stddev(const std::vector<Eigen::Vector3d>& errors) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), sq = Eigen::Vector3d::Zero();
  for (const auto& e : errors) mean += e;
  mean /= static_cast<double>(errors.size());
  for (const auto& e : errors) sq += (e - mean).cwiseAbs2();
  return (sq / static_cast<double>(errors.size() - 1)).cwiseSqrt();
}

TEST(ImuSimulator, WhiteNoiseHasTheDensityTimesSqrtRate) {
  ImuSimulatorConfig config = noiseFree();
  config.noise.gyro_noise_density = 6.6e-5;
  config.noise.accel_noise_density = 9.8e-4;
  config.seed = 11;
  ImuSimulator imu(config);
  const ImuMotion motion = atRest();
  std::vector<Eigen::Vector3d> gyro, accel;
  for (std::uint64_t k = 0; k < 20000; ++k) {
    const ImuSample s = imu.sample(k, motion);
    const ImuKinematics truth = imuKinematics(s.time, motion, config.calibration);
    gyro.push_back(s.angular_velocity - truth.angular_velocity);
    accel.push_back(s.linear_acceleration - truth.specific_force);
  }
  const double gyro_expected = 6.6e-5 * std::sqrt(200.0), accel_expected = 9.8e-4 * std::sqrt(200.0);
  const Eigen::Vector3d gyro_std = stddev(gyro), accel_std = stddev(accel);
  std::printf("gyro std %.4g %.4g %.4g (expected %.4g), accel std %.4g %.4g %.4g (expected %.4g)\n", gyro_std.x(),
              gyro_std.y(), gyro_std.z(), gyro_expected, accel_std.x(), accel_std.y(), accel_std.z(), accel_expected);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(gyro_std[axis], gyro_expected, 0.05 * gyro_expected);
    EXPECT_NEAR(accel_std[axis], accel_expected, 0.05 * accel_expected);
  }
  EXPECT_NEAR(imu.gyroNoiseVariance(), gyro_expected * gyro_expected, 1e-12 * gyro_expected * gyro_expected);
  EXPECT_NEAR(imu.accelNoiseVariance(), accel_expected * accel_expected, 1e-12 * accel_expected * accel_expected);
}

TEST(ImuSimulator, BiasStepsHaveTheRandomWalkTimesSqrtDt) {
  ImuSimulatorConfig config = noiseFree();
  config.noise.gyro_random_walk = 1e-5;
  config.noise.accel_random_walk = 1e-4;
  ImuSimulator imu(config);
  const ImuMotion motion = atRest();
  std::vector<Eigen::Vector3d> gyro_steps, accel_steps;
  ImuSample previous = imu.sample(0, motion);
  ImuKinematics previous_truth = imuKinematics(previous.time, motion, config.calibration);
  // The bias starts at zero.
  EXPECT_LT((previous.angular_velocity - previous_truth.angular_velocity).norm(), 1e-12);
  for (std::uint64_t k = 1; k <= 20000; ++k) {
    const ImuSample s = imu.sample(k, motion);
    const ImuKinematics truth = imuKinematics(s.time, motion, config.calibration);
    gyro_steps.push_back((s.angular_velocity - truth.angular_velocity) -
                         (previous.angular_velocity - previous_truth.angular_velocity));
    accel_steps.push_back((s.linear_acceleration - truth.specific_force) -
                          (previous.linear_acceleration - previous_truth.specific_force));
    previous = s;
    previous_truth = truth;
  }
  const Eigen::Vector3d gyro_std = stddev(gyro_steps), accel_std = stddev(accel_steps);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(gyro_std[axis], 1e-5 * std::sqrt(0.005), 0.05 * 1e-5 * std::sqrt(0.005));
    EXPECT_NEAR(accel_std[axis], 1e-4 * std::sqrt(0.005), 0.05 * 1e-4 * std::sqrt(0.005));
  }
}

TEST(ImuSimulator, SamplesDependOnlyOnSeedAndIndex) {
  ImuSimulatorConfig config;  // the default (ICM-40609) noise
  config.seed = 3;
  const ImuMotion motion = atRest();
  ImuSimulator in_order(config), jumping(config), same_seed(config);
  config.seed = 4;
  ImuSimulator other_seed(config);
  std::vector<ImuSample> samples;
  for (std::uint64_t k = 0; k < 1000; ++k) samples.push_back(in_order.sample(k, motion));
  for (std::uint64_t k = 0; k < 1000; ++k) {
    const ImuSample s = same_seed.sample(k, motion);
    ASSERT_EQ(s.angular_velocity, samples[k].angular_velocity);
    ASSERT_EQ(s.linear_acceleration, samples[k].linear_acceleration);
    const ImuSample o = other_seed.sample(k, motion);
    ASSERT_NE(o.angular_velocity, samples[k].angular_velocity);
    ASSERT_NE(o.linear_acceleration, samples[k].linear_acceleration);
  }
  // Asked for out of order, or skipping samples, the values are the same.
  for (const std::uint64_t k : {999u, 500u, 501u, 998u, 0u, 731u}) {
    const ImuSample s = jumping.sample(k, motion);
    EXPECT_EQ(s.time, samples[k].time);
    EXPECT_EQ(s.angular_velocity, samples[k].angular_velocity) << "k=" << k;
    EXPECT_EQ(s.linear_acceleration, samples[k].linear_acceleration) << "k=" << k;
  }
}

// In real time the clock reads the Unix epoch's seconds: the bias walk starts at the start, zero
// there, and the first sample costs one step, not one per sample since 1970.
TEST(ImuSimulator, TheBiasWalkStartsAtTheStartNotAtTimeZero) {
  ImuSimulatorConfig config = noiseFree();
  config.noise.gyro_random_walk = 1e-3;
  config.noise.accel_random_walk = 1e-2;
  const ImuMotion motion = atRest();
  for (const double start : {1000.0, 1.7e9}) {
    config.start_time = start;
    ImuSimulatorConfig exact_config = noiseFree();
    exact_config.start_time = start;
    ImuSimulator imu(config), exact_imu(exact_config);
    const std::uint64_t first = imu.firstIndexAtOrAfter(start);
    const ImuSample exact = exact_imu.sample(first, motion);
    const ImuSample s = imu.sample(first, motion);
    EXPECT_EQ(s.angular_velocity, exact.angular_velocity) << start;  // no bias yet
    EXPECT_EQ(s.linear_acceleration, exact.linear_acceleration) << start;
    EXPECT_NE(imu.sample(first + 1, motion).angular_velocity, exact_imu.sample(first + 1, motion).angular_velocity)
        << start;
  }
}

TEST(ImuSimulator, SampleTimesAndFirstIndex) {
  ImuSimulator imu(noiseFree());
  EXPECT_EQ(imu.firstIndexAtOrAfter(0.0), 0u);
  EXPECT_EQ(imu.firstIndexAtOrAfter(-1.0), 0u);
  for (std::uint64_t k = 1; k < 5000; k += 7) {
    const double t = imu.sampleTime(k);
    EXPECT_EQ(imu.firstIndexAtOrAfter(t), k);
    EXPECT_EQ(imu.firstIndexAtOrAfter(std::nextafter(t, 0.0)), k);
    EXPECT_EQ(imu.firstIndexAtOrAfter(std::nextafter(t, 1e9)), k + 1);
  }
}

TEST(ImuSimulator, RefusesNegativeNoiseAndZeroRate) {
  ImuSimulatorConfig config;
  config.rate_hz = 0.0;
  EXPECT_THROW(ImuSimulator{config}, std::invalid_argument);
  config = ImuSimulatorConfig{};
  config.noise.gyro_random_walk = -1.0;
  EXPECT_THROW(ImuSimulator{config}, std::invalid_argument);
}

}  // namespace
}  // namespace uampc::raycaster
