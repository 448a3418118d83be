// What a calibration prints and writes: an estimate whose standard deviation is large is said to
// be undetermined and the rig block keeps the believed value; held parameters say why.
#include <gtest/gtest.h>

#include "uampc/calibration/calibration_report.hpp"

namespace uampc::calibration {
namespace {

CalibrationResult fabricated(double pitch_sd) {
  CalibrationResult r;
  r.points = 1000;
  r.terms = 500;
  r.median_distance_before = 0.03;
  r.median_distance_after = 0.012;
  r.distances_before = {0.01, -0.03, 0.05};
  r.distances_after = {0.01, -0.012, 0.004};
  r.parameters = {{"roll_deg", 30.0, 30.5, 0.01, true, ""},
                  {"pitch_deg", 0.0, 0.8, pitch_sd, true, ""},
                  {"yaw_deg", 0.0, 0.0, 0.0, false, "a turn about the motor axis"},
                  {"x", 0.0, 0.012, 0.0004, true, ""},
                  {"y", 0.0, -0.004, 0.0004, true, ""},
                  {"z", 0.0, 0.0, 0.0, false, "a shift along the motor axis"},
                  {"encoder_offset_deg", 0.0, 0.0, 0.0, false, "as yaw"},
                  {"time_offset", 0.0, 0.003, 0.0001, true, ""}};
  return r;
}

TEST(CalibrationReport, AConfidentEstimateIsPrintedWithItsDeviationAndWrittenToTheRigBlock) {
  const CalibrationResult r = fabricated(0.01);
  const std::string text = resultText(r, {});
  EXPECT_NE(text.find("pitch_deg: 0.800 deg +- 0.0100 deg"), std::string::npos) << text;
  EXPECT_NE(text.find("yaw_deg: 0.000 deg held (not observable from a still base: a turn about the motor axis)"),
            std::string::npos)
      << text;
  const std::string block = rigBlock(r, {}, "livox_mid360");
  EXPECT_NE(block.find("lidar_rotation_rpy_deg: [30.5, 0.8, 0]"), std::string::npos) << block;
  EXPECT_NE(block.find("lidar_offset: [0.012, -0.004, 0]"), std::string::npos) << block;
  EXPECT_NE(block.find("time_offset: 0.003"), std::string::npos) << block;
}

TEST(CalibrationReport, AnUncertainEstimateIsUndeterminedAndTheBlockKeepsTheBelief) {
  const CalibrationResult r = fabricated(0.9);
  const std::string text = resultText(r, {});
  EXPECT_NE(text.find("pitch_deg: not determined by this recording (standard deviation 0.900 deg)"), std::string::npos)
      << text;
  EXPECT_EQ(text.find("0.800"), std::string::npos) << "no confident number for it: " << text;
  const std::string block = rigBlock(r, {}, "livox_mid360");
  EXPECT_NE(block.find("lidar_rotation_rpy_deg: [30.5, 0, 0]"), std::string::npos) << block;
  EXPECT_NE(block.find("Held, not observable from a still base: pitch_deg yaw_deg z encoder_offset_deg"),
            std::string::npos)
      << block;
}

TEST(CalibrationReport, TheFigureIsAnSvgWithBothHistograms) {
  const std::string svg = thicknessFigure(fabricated(0.01));
  EXPECT_EQ(svg.rfind("<svg", 0) == 0 || svg.find("<svg") != std::string::npos, true);
  EXPECT_NE(svg.find("believed rig, median 30.0 mm"), std::string::npos);
  EXPECT_NE(svg.find("calibrated, median 12.0 mm"), std::string::npos);
}

}  // namespace
}  // namespace uampc::calibration
