// `uampc calibrate` end to end: a still rig in the corridor recorded to MCAP by a scene's recorder
// (the raycaster's mounting_error_* set, so the simulated rig is off the believed one), calibrated
// from the file: every estimated parameter within its own reported uncertainty of the truth, the
// rig block written; recordings that cannot calibrate refused naming why, with no file written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/calibration/rig_model.hpp"

namespace uampc::test {
namespace {

// The simulator test's block, from index 8 on (simulator_test uses the first ones).
std::string domain(int index) { return domainOverride(DomainBlock::kSimulator, 8 + index); }

struct Printed {
  double value = NAN, stddev = NAN;
};

// "  NAME: VALUE UNIT +- SD UNIT (...)" from calibrate's output, in the rig block's units.
Printed printed(const std::string& output, const std::string& name) {
  const std::regex line("  " + name + ": (-?[0-9.]+) (deg|mm|ms) \\+- ([0-9.]+) (deg|mm|ms)");
  std::smatch m;
  if (!std::regex_search(output, m, line)) return {};
  const double scale = m[2] == "deg" ? 1.0 : 1e-3;
  return {std::stod(m[1]) * scale, std::stod(m[3]) * scale};
}

TEST(Calibrate, FindsTheSimulatedMountingErrorFromARecordingWithinItsUncertainty) {
  const std::string out = freshDirectory("calibrate_mounting_error");
  const std::string scene = sourcePath("tests/scenes/calibration_corridor.yaml");
  CommandResult r = runUampc("launch " + scene + " --out " + out + domain(0) +
                             " --set 'lidar.mounting_error_rpy_deg=[0.8, -0.6, 1.0]'"
                             " --set 'lidar.mounting_error_offset=[0.015, -0.01, 0.02]'"
                             " --set lidar.mounting_error_encoder_deg=2 --set lidar.mounting_error_time_offset=0.006");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string rig = out + "/rig.yaml", svg = out + "/thickness.svg";
  r = runUampc("calibrate " + out + "/recording.mcap --scene " + scene + " --write-rig " + rig + " --svg " + svg);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("uampc calibrate: iteration 1/"), std::string::npos) << r.output;  // progress
  EXPECT_NE(r.output.find("encoder_offset_deg: 0.000 deg held (not observable from a still base"), std::string::npos)
      << r.output;

  const auto believed = frames::MotorLidarCalibration::referenceRig();
  frames::MountingError error;
  error.rotation_rpy = Eigen::Vector3d(0.8, -0.6, 1.0) * M_PI / 180.0;
  error.offset = {0.015, -0.01, 0.02};
  error.encoder_offset = 2.0 * M_PI / 180.0;
  error.time_offset = 0.006;
  const calibration::ObservableRig want =
      calibration::truthInGaugeOf(frames::withMountingError(believed, error), believed);
  const std::pair<const char*, double> expected[] = {{"roll_deg", want.rotation[0] * 180.0 / M_PI},
                                                     {"pitch_deg", want.rotation[1] * 180.0 / M_PI},
                                                     {"x", want.offset[0]},
                                                     {"y", want.offset[1]},
                                                     {"time_offset", want.time_offset[0]}};
  for (const auto& [name, truth] : expected) {
    const Printed p = printed(r.output, name);
    ASSERT_TRUE(std::isfinite(p.value)) << name << " not printed with a deviation:\n" << r.output;
    EXPECT_LT(std::abs(p.value - truth), 3.5 * p.stddev + 1e-9) << name << ": truth " << truth << "\n" << r.output;
  }
  ASSERT_TRUE(std::filesystem::exists(rig));
  EXPECT_TRUE(std::filesystem::exists(svg));
}

TEST(Calibrate, RecordingsThatCannotCalibrateAreRefusedNamingWhyAndNoRigIsWritten) {
  const std::string out = freshDirectory("calibrate_bad_recordings");
  const std::string scene = sourcePath("tests/scenes/calibration_corridor.yaml");
  // 0.6 s at 2 rad/s: 1.2 rad, less than a turn.
  CommandResult r = runUampc("launch " + scene + " --out " + out + domain(1) + " --set clock.duration=0.6");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string rig = out + "/rig.yaml";
  r = runUampc("calibrate " + out + "/recording.mcap --write-rig " + rig);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("one full turn"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(rig));

  r = runUampc("calibrate " + out + "/recording.mcap --write-rig " + rig + " --scan-topic /livox/lidar");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("has no LiDAR scans on /livox/lidar (its topics: "), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(rig));

  r = runUampc("calibrate " + out + "/recording.mcap --motor-topic /motor/states");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("has no motor states on /motor/states"), std::string::npos) << r.output;

  r = runUampc("calibrate " + out + "/missing.mcap");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  r = runUampc("calibrate");
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

}  // namespace
}  // namespace uampc::test
