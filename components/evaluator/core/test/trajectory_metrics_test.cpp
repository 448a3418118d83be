// Tests of pose association, Umeyama alignment, ATE and RPE.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "uampc/evaluator/absolute_trajectory_error.hpp"
#include "uampc/evaluator/motor_activity.hpp"
#include "uampc/evaluator/periodic_grid.hpp"
#include "uampc/evaluator/pose_interpolator.hpp"
#include "uampc/evaluator/relative_pose_error.hpp"
#include "uampc/evaluator/speed_error.hpp"
#include "uampc/evaluator/trajectory_evaluator.hpp"
#include "uampc/evaluator/umeyama.hpp"

namespace uampc::evaluator {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegree = M_PI / 180.0;

Eigen::Isometry3d poseOf(const Eigen::Vector3d& position, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = position;
  return pose;
}

std::vector<Eigen::Vector3d> randomPoints(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> uniform(-20.0, 20.0);
  std::vector<Eigen::Vector3d> points(n);
  for (auto& p : points) p = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng));
  return points;
}

Eigen::Isometry3d knownTransform() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(4.0, -2.5, 1.25);
  return T;
}

// ---------------------------------------------------------------- Umeyama

TEST(Umeyama, RecoversKnownTransformExactlyAndNotTransposed) {
  std::mt19937 rng(1);
  const std::vector<Eigen::Vector3d> source = randomPoints(50, rng);
  const Eigen::Isometry3d T = knownTransform();
  // The rotation is far from symmetric, so applying R^T instead of R would be caught.
  ASSERT_GT((T.linear() - T.linear().transpose()).norm(), 0.5);
  std::vector<Eigen::Vector3d> target;
  for (const auto& s : source) target.push_back(T * s);

  const Eigen::Isometry3d A = umeyamaAlignment(source, target);
  EXPECT_LT((A.linear() - T.linear()).norm(), 1e-12);
  EXPECT_LT((A.translation() - T.translation()).norm(), 1e-12);
  for (std::size_t i = 0; i < source.size(); ++i) {
    EXPECT_LT((A * source[i] - target[i]).norm(), 1e-11);
  }
}

TEST(Umeyama, RecoversKnownTransformFromNoisyPoints) {
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.05);
  const std::vector<Eigen::Vector3d> source = randomPoints(2000, rng);
  const Eigen::Isometry3d T = knownTransform();
  std::vector<Eigen::Vector3d> target;
  for (const auto& s : source) target.push_back(T * s + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));

  const Eigen::Isometry3d A = umeyamaAlignment(source, target);
  EXPECT_LT(Eigen::AngleAxisd(A.linear().transpose() * T.linear()).angle(), 1e-3);
  EXPECT_LT((A.translation() - T.translation()).norm(), 1e-2);

  // Same answer as Eigen's own implementation (without scaling).
  Eigen::Matrix3Xd src(3, source.size()), dst(3, target.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    src.col(static_cast<Eigen::Index>(i)) = source[i];
    dst.col(static_cast<Eigen::Index>(i)) = target[i];
  }
  const Eigen::Matrix4d eigen = Eigen::umeyama(src, dst, false);
  EXPECT_LT((A.matrix() - eigen).norm(), 1e-9);
}

TEST(Umeyama, NeverReturnsAReflection) {
  // Coplanar points and a mirrored target: a plain U V^T can have det -1 here.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  std::vector<Eigen::Vector3d> source, mirrored, rotated;
  const Eigen::Isometry3d T = knownTransform();
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector3d p(uniform(rng), uniform(rng), 0.0);
    source.push_back(p);
    mirrored.push_back(Eigen::Vector3d(p.x(), -p.y(), p.z()));
    rotated.push_back(T * p);
  }
  const Eigen::Isometry3d planar = umeyamaAlignment(source, rotated);
  EXPECT_NEAR(planar.linear().determinant(), 1.0, 1e-12);
  EXPECT_LT((planar.linear() - T.linear()).norm(), 1e-10);

  std::vector<Eigen::Vector3d> source3d = randomPoints(30, rng), mirrored3d;
  for (const auto& p : source3d) mirrored3d.push_back(Eigen::Vector3d(p.x(), -p.y(), p.z()));
  EXPECT_NEAR(umeyamaAlignment(source3d, mirrored3d).linear().determinant(), 1.0, 1e-12);
}

TEST(Umeyama, DegenerateInputs) {
  EXPECT_THROW(umeyamaAlignment({Eigen::Vector3d::Zero()}, {}), std::invalid_argument);
  EXPECT_TRUE(umeyamaAlignment({}, {}).isApprox(Eigen::Isometry3d::Identity()));
  const Eigen::Isometry3d one = umeyamaAlignment({Eigen::Vector3d(1, 2, 3)}, {Eigen::Vector3d(2, 2, 2)});
  EXPECT_LT((one * Eigen::Vector3d(1, 2, 3) - Eigen::Vector3d(2, 2, 2)).norm(), 1e-12);
}

// ---------------------------------------------------------------- interpolation

TEST(PoseInterpolator, LinearPositionSlerpAttitudeInsideRangeOnly) {
  const PoseInterpolator truth({{1.0, poseOf({10, 0, 0}, 0.4)}, {0.0, poseOf({0, 0, 0}, 0.0)}});
  ASSERT_EQ(truth.size(), 2u);
  const auto middle = truth(0.25);
  ASSERT_TRUE(middle.has_value());
  EXPECT_LT((middle->translation() - Eigen::Vector3d(2.5, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(middle->linear()).angle(), 0.1, 1e-12);
  EXPECT_TRUE(truth(0.0).has_value());  // end points are inside
  EXPECT_TRUE(truth(1.0).has_value());
  EXPECT_FALSE(truth(-1e-9).has_value());
  EXPECT_FALSE(truth(1.0 + 1e-9).has_value());
  EXPECT_FALSE(truth(kNaN).has_value());
  EXPECT_FALSE(PoseInterpolator()(0.0).has_value());
}

TEST(PoseInterpolator, SortsDropsDuplicatesAndNonFiniteTimes) {
  PoseInterpolator truth({{2.0, poseOf({2, 0, 0}, 0)},
                          {0.0, poseOf({0, 0, 0}, 0)},
                          {2.0, poseOf({99, 0, 0}, 0)},
                          {kNaN, poseOf({0, 0, 0}, 0)}});
  EXPECT_EQ(truth.size(), 2u);
  EXPECT_EQ(truth.droppedPoses(), 2u);
  EXPECT_NEAR(truth(2.0)->translation().x(), 2.0, 1e-12);  // the first of the equal times stays
  EXPECT_TRUE(truth.add({3.0, poseOf({3, 0, 0}, 0)}));
  EXPECT_TRUE(truth.add({1.0, poseOf({5, 0, 0}, 0)}));  // out of order: inserted at its place
  EXPECT_FALSE(truth.add({1.0, poseOf({7, 0, 0}, 0)}));
  EXPECT_NEAR(truth(0.5)->translation().x(), 2.5, 1e-12);
  EXPECT_NEAR(truth(1.5)->translation().x(), 3.5, 1e-12);
  EXPECT_DOUBLE_EQ(truth.endTime(), 3.0);
}

// A long run's ground truth is kept as a window: dropping what lies before a time leaves every
// lookup from that time on as it was, and erases in batches only.
TEST(PoseInterpolator, DropBeforeKeepsEveryLookupFromThatTimeOn) {
  PoseInterpolator truth;
  for (int i = 0; i <= 100; ++i) truth.add({i * 0.1, poseOf({i * 1.0, 0, 0}, 0)});
  const double at = 5.05;  // between the poses at 5.0 and 5.1
  const Eigen::Vector3d before = truth(at)->translation();
  truth.dropBefore(at, 100);  // 50 poses could go: fewer than a batch, nothing is erased
  EXPECT_EQ(truth.size(), 101u);
  truth.dropBefore(at, 10);
  EXPECT_EQ(truth.size(), 51u);  // from the pose at 5.0 on
  EXPECT_DOUBLE_EQ(truth.startTime(), 5.0);
  EXPECT_EQ(truth(at)->translation(), before);
  EXPECT_FALSE(truth(4.9).has_value());
  truth.dropBefore(-1.0, 1);  // before every pose: nothing to drop
  EXPECT_EQ(truth.size(), 51u);
}

// Ground truth at 10 Hz moving at 10 m/s along x; an estimate stamped between two samples is
// compared with the truth at its own time. Nearest-neighbour association within 0.1 s would
// compare it with the sample 0.05 s away, 0.5 m off.
TEST(TrajectoryEvaluator, AssociatesByExactTimeNotNearestPose) {
  std::vector<TimedPose> samples;
  for (int k = 0; k <= 100; ++k) samples.push_back({0.1 * k, poseOf({1.0 * k, 0, 0}, 0.0)});
  const PoseInterpolator truth(samples);
  TrajectoryEvaluator evaluator([&truth](double t) { return truth(t); });
  for (int k = 0; k < 100; ++k) {
    const double t = 0.1 * k + 0.05;
    EXPECT_TRUE(evaluator.addEstimate(t, poseOf({10.0 * t, 0, 0}, 0.0)));
  }
  const TrajectoryReport report = evaluator.report();
  EXPECT_EQ(report.paired, 100u);
  EXPECT_LT(report.ate.unaligned.max, 1e-9);
  EXPECT_LT(report.ate.unaligned.rmse, 1e-9);
}

TEST(TrajectoryEvaluator, EstimatesOutsideGroundTruthAreUnpairedNotPairedWrongly) {
  const PoseInterpolator truth({{10.0, poseOf({0, 0, 0}, 0)}, {20.0, poseOf({10, 0, 0}, 0)}});
  TrajectoryEvaluator evaluator([&truth](double t) { return truth(t); });
  EXPECT_FALSE(evaluator.addEstimate(9.99, poseOf({0, 0, 0}, 0)));
  EXPECT_FALSE(evaluator.addEstimate(20.01, poseOf({10, 0, 0}, 0)));
  EXPECT_FALSE(evaluator.addEstimate(kNaN, poseOf({10, 0, 0}, 0)));
  EXPECT_FALSE(evaluator.addEstimate(15.0, poseOf({kNaN, 0, 0}, 0)));
  EXPECT_TRUE(evaluator.addEstimate(15.0, poseOf({5, 0, 1}, 0)));
  const TrajectoryReport report = evaluator.report();
  EXPECT_EQ(report.estimates, 5u);
  EXPECT_EQ(report.paired, 1u);
  EXPECT_EQ(report.unpaired, 2u);
  EXPECT_EQ(report.invalid, 2u);
  EXPECT_NEAR(report.ate.unaligned.rmse, 1.0, 1e-12);
  ASSERT_EQ(report.rpe.size(), 2u);
  EXPECT_DOUBLE_EQ(report.rpe[0].segment_length, 10.0);
  EXPECT_DOUBLE_EQ(report.rpe[1].segment_length, 100.0);
  ASSERT_EQ(evaluator.pairedGroundTruth().size(), 1u);
  EXPECT_NEAR(evaluator.pairedGroundTruth()[0].pose.translation().x(), 5.0, 1e-12);
}

TEST(TrajectoryEvaluator, DistanceIsTheGroundTruthPathOverTheEvaluatedSpanOnly) {
  // Ground truth: 10 m east in 10 s, then 5 m north in 5 s, then 20 m east in 20 s (35 m in all).
  const PoseInterpolator truth({{0.0, poseOf({0, 0, 0}, 0)},
                                {10.0, poseOf({10, 0, 0}, 0)},
                                {15.0, poseOf({10, 5, 0}, 0)},
                                {35.0, poseOf({30, 5, 0}, 0)}});
  TrajectoryEvaluator evaluator([&truth](double t) { return truth(t); });
  // Estimates from 5 s to 20 s (the span evaluated) at 10 Hz, given out of order, far off the
  // truth (the distance is the truth's, not the estimate's), plus two outside the ground truth.
  for (int k = 200; k >= 50; --k) evaluator.addEstimate(0.1 * k, poseOf({0, 0, 0.01 * k}, 0));
  EXPECT_FALSE(evaluator.addEstimate(-1.0, poseOf({0, 0, 0}, 0)));
  EXPECT_FALSE(evaluator.addEstimate(40.0, poseOf({0, 0, 0}, 0)));
  // Over 5..20 s the truth goes 5 m east (to the corner), 5 m north, 5 m east: 15 m. The corner
  // at 10 s and at 15 s are estimate times, so the chords follow the path exactly.
  EXPECT_NEAR(evaluator.report().distance, 15.0, 1e-9);
  TrajectoryEvaluator nothing([&truth](double t) { return truth(t); });
  EXPECT_EQ(nothing.report().distance, 0.0);
}

TEST(TrajectoryEvaluator, SpeedErrorIsTakenInTimeOrderWhateverOrderTheEstimatesCame) {
  // The estimate follows the truth (1 m/s east) but climbs at 0.1 m/s; given newest first.
  const PoseInterpolator truth({{0.0, poseOf({0, 0, 0}, 0)}, {30.0, poseOf({30, 0, 0}, 0)}});
  TrajectoryEvaluator evaluator([&truth](double t) { return truth(t); });
  for (int k = 250; k >= 0; --k) evaluator.addEstimate(0.1 * k, poseOf({0.1 * k, 0, 0.01 * k}, 0));
  const TrajectoryReport report = evaluator.report();
  EXPECT_NEAR(report.speed_error.max, 0.1, 1e-6);
  EXPECT_FALSE(report.speed_error.first_runaway_time.has_value());
  EXPECT_NEAR(report.distance, 25.0, 1e-9);
}

// ---------------------------------------------------------------- ATE

TEST(AbsoluteTrajectoryError, ConstantOffsetIsTheOffsetUnalignedAndZeroAligned) {
  AbsoluteTrajectoryError ate;
  const Eigen::Vector3d offset(0.3, -0.4, 0.0);  // 0.5 m
  for (int k = 0; k < 200; ++k) {
    const double a = 0.05 * k;
    const Eigen::Vector3d truth(20.0 * std::cos(a), 20.0 * std::sin(a), 0.1 * k);
    ate.add(0.1 * k, truth + offset, truth);
  }
  const AteReport report = ate.report();
  EXPECT_EQ(report.unaligned.count, 200u);
  EXPECT_NEAR(report.unaligned.rmse, 0.5, 1e-12);
  EXPECT_NEAR(report.unaligned.mean, 0.5, 1e-12);
  EXPECT_NEAR(report.unaligned.median, 0.5, 1e-12);
  EXPECT_NEAR(report.unaligned.max, 0.5, 1e-12);
  EXPECT_LT(report.aligned.rmse, 1e-9);
  EXPECT_LT((report.alignment.translation() + offset).norm(), 1e-9);
}

TEST(AbsoluteTrajectoryError, StatisticsAndSeriesSortedByTime) {
  AbsoluteTrajectoryError ate;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  ate.add(3.0, {3, 0, 0}, zero);
  ate.add(1.0, {1, 0, 0}, zero);
  ate.add(4.0, {0, 4, 0}, zero);
  ate.add(2.0, {0, 0, 2}, zero);
  EXPECT_FALSE(ate.add(5.0, {kNaN, 0, 0}, zero));
  EXPECT_EQ(ate.rejected(), 1u);
  const AteReport report = ate.report();
  EXPECT_NEAR(report.unaligned.rmse, std::sqrt(7.5), 1e-12);
  EXPECT_NEAR(report.unaligned.mean, 2.5, 1e-12);
  EXPECT_NEAR(report.unaligned.median, 2.5, 1e-12);
  EXPECT_NEAR(report.unaligned.max, 4.0, 1e-12);
  ASSERT_EQ(report.series.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(report.series[k].time, k + 1.0);
    EXPECT_NEAR(report.series[k].error, k + 1.0, 1e-12);
  }
}

TEST(AbsoluteTrajectoryError, EmptyIsNaNNotZero) {
  const AteReport report = AbsoluteTrajectoryError().report();
  EXPECT_EQ(report.unaligned.count, 0u);
  EXPECT_TRUE(std::isnan(report.unaligned.rmse));
  EXPECT_TRUE(std::isnan(report.aligned.rmse));
  EXPECT_TRUE(std::isnan(AbsoluteTrajectoryError().rmse().unaligned));
  EXPECT_TRUE(std::isnan(AbsoluteTrajectoryError().rmse().aligned));
}

// rmse() is report()'s two RMSEs to the last bit, pairs in any order (the running figure the
// evaluator publishes, and metrics.json at the end, must agree).
TEST(AbsoluteTrajectoryError, RmseAloneIsTheReportsToTheBit) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  AbsoluteTrajectoryError ate;
  const Eigen::Isometry3d drift =
      Eigen::Translation3d(0.4, -0.2, 0.1) * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ());
  for (int k = 0; k < 1000; ++k) {
    const double t = (k * 7919) % 1000 * 0.1;  // not in time order
    const Eigen::Vector3d truth(t, std::sin(t), 0.1 * t);
    ate.add(t, drift * truth + Eigen::Vector3d(noise(random), noise(random), noise(random)), truth);
  }
  const AteReport report = ate.report();
  const AteRmse rmse = ate.rmse();
  EXPECT_EQ(rmse.unaligned, report.unaligned.rmse);
  EXPECT_EQ(rmse.aligned, report.aligned.rmse);
  EXPECT_LT(rmse.aligned, rmse.unaligned);
}

// ---------------------------------------------------------------- RPE

TEST(RelativePoseError, PerfectEstimateHasZeroError) {
  RelativePoseError rpe;
  for (int k = 0; k < 600; ++k) {  // a 0.5 m-step curve with turning attitude, ~300 m
    const double a = 0.01 * k;
    const Eigen::Isometry3d truth = poseOf({50.0 * std::sin(a), 50.0 * (1 - std::cos(a)), 0.01 * k}, a);
    rpe.add(0.1 * k, truth, truth);
  }
  for (const double d : {10.0, 100.0}) {
    const RpeReport report = rpe.report(d);
    EXPECT_GT(report.translation.count, 100u) << d;
    EXPECT_LT(report.translation.max, 1e-9) << d;
    EXPECT_LT(report.translation_percent.max, 1e-9) << d;
    EXPECT_LT(report.rotation_deg.max, 1e-6) << d;
  }
  const RpeReport too_long = rpe.report(1000.0);
  EXPECT_EQ(too_long.translation.count, 0u);
  EXPECT_TRUE(std::isnan(too_long.translation.rmse));
  EXPECT_THROW(rpe.report(0.0), std::invalid_argument);
  EXPECT_THROW(rpe.report(-10.0), std::invalid_argument);
}

TEST(RelativePoseError, ScaleDriftGivesItsPercentage) {
  // Straight line at 1 m per pose (exact distances), heading 30 degrees off the direction of
  // travel; the estimate travels 2% too far.
  RelativePoseError rpe;
  const double scale_drift = 0.02;
  const Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  for (int k = 300; k >= 0; --k) {  // added backwards: the report sorts by time
    rpe.add(0.1 * k, poseOf((1.0 + scale_drift) * k * direction, 30 * kDegree), poseOf(k * direction, 30 * kDegree));
  }
  const RpeReport ten = rpe.report(10.0);
  EXPECT_EQ(ten.translation.count, 291u);  // starts 0..290 reach 10 m
  EXPECT_NEAR(ten.translation_percent.mean, 2.0, 1e-9);
  EXPECT_NEAR(ten.translation_percent.max, 2.0, 1e-9);
  EXPECT_NEAR(ten.translation.rmse, 0.2, 1e-9);
  EXPECT_LT(ten.rotation_deg.max, 1e-9);
  const RpeReport hundred = rpe.report(100.0);
  EXPECT_EQ(hundred.translation.count, 201u);
  EXPECT_NEAR(hundred.translation.rmse, 2.0, 1e-9);
  EXPECT_NEAR(hundred.translation_percent.mean, 2.0, 1e-9);
}

TEST(RelativePoseError, HeadingDriftGivesItsRotationPerSegment) {
  // The estimate's heading drifts by 0.1 degree per metre: 1 degree per 10 m segment.
  RelativePoseError rpe;
  for (int k = 0; k <= 50; ++k) {
    rpe.add(0.1 * k, poseOf({1.0 * k, 0, 0}, 0.1 * kDegree * k), poseOf({1.0 * k, 0, 0}, 0.0));
  }
  const RpeReport report = rpe.report(10.0);
  EXPECT_EQ(report.rotation_deg.count, 41u);
  EXPECT_NEAR(report.rotation_deg.mean, 1.0, 1e-9);
  EXPECT_NEAR(report.rotation_deg.max, 1.0, 1e-9);
}

TEST(SpeedError, FindsWhenTheEstimatedSpeedRunsAwayAndIgnoresFrameJitter) {
  // Truth at 1.5 m/s along x, 10 Hz, 20 s. The estimate jitters by +-2 cm every frame (0.4 m/s
  // frame to frame), and from 12 s on its speed drifts away, 0.5 m/s more each second.
  std::vector<TimedPose> truths, estimates;
  double drift = 0.0;
  for (int k = 0; k <= 200; ++k) {
    const double t = 0.1 * k;
    TimedPose truth{t, Eigen::Isometry3d::Identity()};
    truth.pose.translation() = Eigen::Vector3d(1.5 * t, 0.0, 0.0);
    if (t > 12.0) drift += 0.5 * (t - 12.0) * 0.1;
    TimedPose estimate = truth;
    estimate.pose.translation() += Eigen::Vector3d(drift, (k % 2 ? 0.02 : -0.02), 0.0);
    truths.push_back(truth);
    estimates.push_back(estimate);
  }
  const SpeedErrorReport report = speedError(estimates, truths);
  ASSERT_TRUE(report.first_runaway_time.has_value());
  // The speed error over [t - 1, t] first passes 1 m/s at about t = 14.5 s (0.5 m/s^2 from 12 s).
  EXPECT_NEAR(*report.first_runaway_time, 14.5, 0.3);
  EXPECT_GT(report.max, 3.0);
  // The same without the drift: jitter alone is no runaway.
  for (std::size_t i = 0; i < estimates.size(); ++i) {
    estimates[i].pose.translation().x() = truths[i].pose.translation().x();
  }
  const SpeedErrorReport steady = speedError(estimates, truths);
  EXPECT_FALSE(steady.first_runaway_time.has_value());
  EXPECT_LT(steady.max, 0.05);
}

TEST(MotorActivity, ChangesPerControlPeriodNotPerEncoderSample) {
  // A command alternating 3 and 5 rad/s every 0.1 s, the motor following it exactly, states at
  // 200 Hz: every period changes by 2 rad/s, whatever the encoder rate.
  MotorActivity activity(0.1);
  for (int i = 0; i < 2000; ++i) {
    const double t = i * 0.005;
    const double command = (static_cast<int>(std::floor(t / 0.1 + 1e-9)) % 2 == 0) ? 3.0 : 5.0;
    activity.add(t, command, command);
  }
  const MotorActivityReport r = activity.report();
  EXPECT_NEAR(r.mean_speed, 4.0, 1e-9);
  EXPECT_NEAR(r.speed_std, 1.0, 1e-9);
  EXPECT_NEAR(r.command_change_rms, 2.0, 1e-9);
  EXPECT_NEAR(r.speed_change_rms, 2.0, 1e-9);
  EXPECT_EQ(r.periods, 99u);
}

TEST(MotorActivity, ConstantSpeedDoesNotChangeAndBadSamplesAreIgnored) {
  MotorActivity activity(0.1);
  for (int i = 0; i < 400; ++i) activity.add(i * 0.005, 3.6, 3.6);
  activity.add(NAN, 100.0, 100.0);
  activity.add(0.5, 100.0, 100.0);  // not after the last state
  const MotorActivityReport r = activity.report();
  EXPECT_NEAR(r.mean_speed, 3.6, 1e-12);
  EXPECT_EQ(r.command_change_rms, 0.0);
  EXPECT_EQ(r.speed_change_rms, 0.0);
  EXPECT_THROW(MotorActivity(0.0), std::invalid_argument);
}

TEST(MotorActivity, ATimeFarAheadIsOneMorePeriodNotAHang) {
  // A stamp 2^31 s ahead at a 1 ms grid: stepping there one period at a time would never end.
  MotorActivity activity(0.001);
  activity.add(0.0, 1.0, 1.0);
  activity.add(2147483647.5, 3.0, 3.0);
  activity.add(2147483647.6, 3.0, 3.0);
  const MotorActivityReport r = activity.report();
  EXPECT_EQ(r.periods, 2u);
  EXPECT_NEAR(r.command_change_rms, std::sqrt(2.0), 1e-12);
}

TEST(PeriodicGrid, FirstPointStrictlyAfterTheTime) {
  EXPECT_DOUBLE_EQ(firstGridPointAfter(20.0, 5.0, 20.0), 20.0);   // not reached yet
  EXPECT_DOUBLE_EQ(firstGridPointAfter(20.0, 20.0, 20.0), 40.0);  // on a point: the next one
  EXPECT_DOUBLE_EQ(firstGridPointAfter(20.0, 79.9, 20.0), 80.0);
  EXPECT_NEAR(firstGridPointAfter(0.0, 2147483647.0, 0.001), 2147483647.001, 1e-5);
  const double huge = 1e300;  // the period is below a double's resolution there
  EXPECT_GT(firstGridPointAfter(0.0, huge, 0.001), huge);
  EXPECT_EQ(firstGridPointAfter(3.0, kNaN, 1.0), 3.0);
}

}  // namespace
}  // namespace uampc::evaluator
