#include "calibrate/calibrate_command.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/calibration/calibration_report.hpp"
#include "uampc/calibration/rig_estimator.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/runtime/component_library.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc::app {
namespace {

struct BelievedRig {
  frames::MotorLidarCalibration calibration = frames::MotorLidarCalibration::referenceRig();
  std::string lidar_model = "livox_mid360";
};

// The rig the scene's components would be given (its rig: block, --set rig.*, the defaults).
BelievedRig believedRig(const CalibrateOptions& o) {
  BelievedRig rig;
  if (o.scene.empty()) return rig;
  std::vector<Override> overrides;
  for (const auto& text : o.overrides) overrides.push_back(parseOverride(text));
  ComponentCatalog catalog;
  const Scene scene = loadScene(o.scene, overrides, catalog, false);
  rig.calibration = adapters::rigCalibration(scene.rig);
  if (const auto it = scene.rig.find("lidar_model"); it != scene.rig.end()) {
    rig.lidar_model = std::get<std::string>(it->second);
  }
  return rig;
}

// Outputs that exist are refused without --overwrite (docs/decisions/no-silent-overwrite.md),
// before the minutes of estimation.
std::string existingOutput(const CalibrateOptions& o) {
  for (const std::string& path : {o.write_rig, o.svg}) {
    if (!path.empty() && !o.overwrite && std::filesystem::exists(path)) return path;
  }
  return "";
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int calibrateCommand(const CalibrateOptions& o) {
  BelievedRig believed;
  try {
    believed = believedRig(o);
  } catch (const SceneError& e) {
    std::cerr << e.what() << "\n";
    return kCommandLineError;
  }
  if (const std::string existing = existingOutput(o); !existing.empty()) {
    std::cerr << "uampc calibrate: " << existing << " exists; --overwrite replaces it\n";
    return 1;
  }
  calibration::EstimatorConfig config;
  config.max_points = o.max_points;
  config.max_off_plane = o.max_off_plane;
  calibration::CalibrationResult result;
  try {
    std::cerr << "uampc calibrate: reading " << o.recording << "\n";
    const calibration::RigRecording recording = readRigRecording(o.recording, o.topics);
    result = calibration::estimateRig(recording, believed.calibration, config,
                                      [](const std::string& line) { std::cerr << "uampc " << line << "\n"; });
  } catch (const calibration::CalibrationError& e) {
    std::cerr << "uampc calibrate: " << o.recording << " cannot calibrate the rig: " << e.what()
              << " (docs/user/calibration.md)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "uampc calibrate: " << e.what() << "\n";
    return 1;
  }
  const calibration::TrustLimits limits;
  std::cout << calibration::resultText(result, limits);
  try {
    const std::string block = calibration::rigBlock(result, limits, believed.lidar_model);
    if (!o.write_rig.empty()) writeText(o.write_rig, block);
    if (!o.svg.empty()) writeText(o.svg, calibration::thicknessFigure(result));
    if (o.write_rig.empty()) std::cout << "\n" << block;
  } catch (const std::exception& e) {
    std::cerr << "uampc calibrate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

void addCalibrateCommand(CommandSet& commands) {
  auto options = std::make_shared<CalibrateOptions>();
  CalibrateOptions& o = *options;
  CLI::App* sub = commands.add(
      "calibrate",
      "uampc calibrate RECORDING.mcap [--scene SCENE.yaml [--set rig.NAME=VALUE ...]] [--write-rig FILE]\n"
      "[--svg FILE] [--overwrite] [--scan-topic T] [--motor-topic T] [--ground-truth-topic T]\n[--max-points N] "
      "[--max-off-plane M]",
      "Calibrate the rig from a recording (uampc record, or a scene's recorder) of the rig standing still\n"
      "while the motor turns at least one full turn, at varying speed: the LiDAR's roll and pitch on the\n"
      "rotor, its offset from the motor axis and the LiDAR-to-encoder clock offset, with their standard\n"
      "deviations, found by making the scene seen at different motor angles agree. Yaw about the motor\n"
      "axis, the encoder's zero and the offset along the axis cannot be seen from a still base and are\n"
      "held at the believed rig's values (docs/user/calibration.md). Prints the result and a rig: block\n"
      "to paste into a scene. Exit code 1, and no file written, when the recording cannot calibrate the\n"
      "rig (no scans, no motor states, less than a turn, too few planes, a base that moved).");
  sub->add_option("RECORDING.mcap", o.recording, "The recording (MCAP as rosbag2 writes it).")
      ->required()
      ->type_name("");
  sub->add_option("--scene", o.scene,
                  "The believed rig: the rig: block of this scene (default: the reference rig, a Mid-360\n"
                  "tilted 30 degrees about x, no offsets).")
      ->type_name("SCENE.yaml");
  sub->add_option("--set", o.overrides, "Change the scene's rig before calibrating: rig.NAME=VALUE.")
      ->type_name("NAME=VALUE");
  sub->add_option("--write-rig", o.write_rig, "Write the calibrated rig: block to FILE (else print it).")
      ->type_name("FILE");
  sub->add_option("--svg", o.svg, "Write a figure of the map's points off its planes before and after.")
      ->type_name("FILE");
  sub->add_flag("--overwrite", o.overwrite, "Replace --write-rig and --svg files that exist.");
  sub->add_option("--scan-topic", o.topics.scans, "The LiDAR's PointCloud2 topic (default /lidar/points).")
      ->type_name("T");
  sub->add_option("--motor-topic", o.topics.motor, "The motor's JointState topic (default /motor/state).")
      ->type_name("T");
  sub->add_option("--ground-truth-topic", o.topics.ground_truth,
                  "A PoseStamped of the base, when recorded (default /ground_truth/pose): the calibration is\n"
                  "refused if it moved.")
      ->type_name("T");
  sub->add_option("--max-points", o.max_points,
                  "Points sampled evenly from all scans (default 150000): more is slower and a little surer.")
      ->check(CLI::Range(1000, 100000000))
      ->type_name("N");
  sub->add_option("--max-off-plane", o.max_off_plane,
                  "Refuse when a quarter of the calibrated map's points lie more than M metres off its planes\n"
                  "(default 0.04): a base or a scene that moved, or a LiDAR noisier than that.")
      ->check(command_line::kFinite)
      ->check(CLI::Range(0.001, 10.0))
      ->type_name("M");
  commands.onRun(sub, [options] { return calibrateCommand(*options); });
}

}  // namespace uampc::app
