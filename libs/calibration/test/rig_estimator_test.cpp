// The estimator against recordings cast by the simulator's core: a known mounting error found
// within the estimator's own uncertainty, the true rig found unchanged, and each recording that
// cannot calibrate refused naming why.
#include <gtest/gtest.h>

#include <cstdio>

#include "simulated_recording.hpp"
#include "uampc/calibration/rig_estimator.hpp"
#include "uampc/calibration/rig_model.hpp"

namespace uampc::calibration {
namespace {

constexpr double kDeg = M_PI / 180.0;

frames::MountingError knownError() {
  frames::MountingError e;
  e.rotation_rpy = Eigen::Vector3d(1.0, -0.7, 2.0) * kDeg;
  e.offset = {0.02, -0.015, 0.03};
  e.encoder_offset = 1.5 * kDeg;
  e.time_offset = 0.005;
  return e;
}

// Every estimated parameter within 3.5 standard deviations of what the truth is in the
// estimator's gauge, and each standard deviation small enough to mean something.
void expectFound(const CalibrationResult& r, const frames::MotorLidarCalibration& truth,
                 const frames::MotorLidarCalibration& believed) {
  const ObservableRig want = truthInGaugeOf(truth, believed);
  const double expected[] = {want.rotation[0] / kDeg, want.rotation[1] / kDeg, want.offset[0], want.offset[1],
                             want.time_offset[0]};
  const char* names[] = {"roll_deg", "pitch_deg", "x", "y", "time_offset"};
  const double useful[] = {0.05, 0.05, 0.002, 0.002, 0.0005};
  for (int i = 0; i < 5; ++i) {
    const ParameterEstimate* p = nullptr;
    for (const auto& q : r.parameters)
      if (q.name == names[i]) p = &q;
    ASSERT_NE(p, nullptr) << names[i];
    std::printf("%-12s truth %12.6f estimate %12.6f sd %10.6f (%.1f sd off)\n", names[i], expected[i], p->value,
                p->stddev, std::abs(p->value - expected[i]) / p->stddev);
    ASSERT_TRUE(p->estimated) << names[i];
    EXPECT_LT(p->stddev, useful[i]) << names[i];
    EXPECT_LT(std::abs(p->value - expected[i]), 3.5 * p->stddev) << names[i];
  }
}

TEST(RigEstimator, FindsAKnownMountingErrorWithinItsOwnUncertainty) {
  const auto believed = frames::MotorLidarCalibration::referenceRig();
  test::SimulatedRig rig;
  rig.truth = frames::withMountingError(believed, knownError());
  const CalibrationResult r = estimateRig(test::simulatedRecording(rig), believed, {},
                                          [](const std::string& line) { std::printf("%s\n", line.c_str()); });
  expectFound(r, rig.truth, believed);
  EXPECT_LT(r.median_distance_after, 0.5 * r.median_distance_before);
  // What cannot be seen from a still base is held at the believed values, and said so.
  for (const char* held : {"yaw_deg", "z", "encoder_offset_deg"}) {
    for (const auto& p : r.parameters) {
      if (p.name != held) continue;
      EXPECT_FALSE(p.estimated) << held;
      EXPECT_EQ(p.value, p.believed) << held;
      EXPECT_FALSE(p.held_because.empty()) << held;
    }
  }
}

TEST(RigEstimator, TheTrueRigComesBackUnchangedWithinItsUncertainty) {
  const auto believed = frames::MotorLidarCalibration::referenceRig();
  test::SimulatedRig rig;
  rig.truth = believed;
  rig.seed = 2;
  const CalibrationResult r = estimateRig(test::simulatedRecording(rig), believed);
  expectFound(r, believed, believed);
}

TEST(RigEstimator, AtOneSpeedTheClockOffsetIsHeldAndSaidSo) {
  const auto believed = frames::MotorLidarCalibration::referenceRig();
  test::SimulatedRig rig;
  rig.speed_swing = 0.0;
  rig.seconds = 2.5;
  const CalibrationResult r = estimateRig(test::simulatedRecording(rig), believed);
  for (const auto& p : r.parameters) {
    if (p.name != "time_offset") continue;
    EXPECT_FALSE(p.estimated);
    EXPECT_NE(p.held_because.find("one speed"), std::string::npos) << p.held_because;
  }
}

std::string refusal(const RigRecording& recording) {
  try {
    estimateRig(recording, frames::MotorLidarCalibration::referenceRig(), {},
                [](const std::string& line) { std::printf("%s\n", line.c_str()); });
  } catch (const CalibrationError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(RigEstimator, RefusesRecordingsThatCannotCalibrateNamingWhy) {
  test::SimulatedRig rig;
  rig.seconds = 2.5;
  const RigRecording good = test::simulatedRecording(rig);

  RigRecording no_scans = good;
  no_scans.scans.clear();
  EXPECT_NE(refusal(no_scans).find("no LiDAR scans"), std::string::npos) << refusal(no_scans);

  RigRecording no_motor = good;
  no_motor.encoder.clear();
  EXPECT_NE(refusal(no_motor).find("no motor states"), std::string::npos) << refusal(no_motor);

  RigRecording part_turn = good;  // the scans of the first 1.2 s: 4.3 rad
  while (part_turn.scans.back().stamp > 1.2) part_turn.scans.pop_back();
  EXPECT_NE(refusal(part_turn).find("one full turn"), std::string::npos) << refusal(part_turn);

  RigRecording few_planes = good;  // a handful of points a scan
  for (auto& scan : few_planes.scans) {
    scan.points.resize(20);
    scan.time_offsets.resize(20);
  }
  EXPECT_NE(refusal(few_planes).find("planes were found"), std::string::npos) << refusal(few_planes);

  test::SimulatedRig moving = rig;
  moving.with_ground_truth = true;
  moving.base_velocity = {0.1, 0.2, 0.05};
  const RigRecording with_truth = test::simulatedRecording(moving);
  EXPECT_NE(refusal(with_truth).find("the base moved"), std::string::npos) << refusal(with_truth);
  RigRecording without_truth = with_truth;  // the map tells
  without_truth.base_poses.clear();
  const std::string why = refusal(without_truth);
  EXPECT_TRUE(why.find("does not agree with itself") != std::string::npos ||
              why.find("planes were found") != std::string::npos)
      << why;
}

}  // namespace
}  // namespace uampc::calibration
