// `uampc calibrate RECORDING.mcap [--scene SCENE.yaml] [--write-rig FILE] [--svg FILE] ...`: the
// rig's calibration from a recording of the rig standing still while the motor turns
// (docs/user/calibration.md). A thin adapter: the recording is read here
// (calibrate/recording_input), the estimate is libs/calibration's.
#pragma once

#include <string>
#include <vector>

#include "calibrate/recording_input.hpp"
#include "cli/command_set.hpp"

namespace uampc::app {

struct CalibrateOptions {
  std::string recording;
  std::string scene;                   // the believed rig from its rig: block; empty: the reference rig
  std::vector<std::string> overrides;  // --set rig.NAME=VALUE on the scene
  std::string write_rig;               // the rig: block to this file
  std::string svg;                     // the map's thickness before and after
  bool overwrite = false;
  RecordingTopics topics;
  std::size_t max_points = 150000;
  double max_off_plane = 0.04;  // m
};

// Exit codes: 0 calibrated; 1 a recording that cannot calibrate the rig (named) or a file that
// cannot be read or written; 2 command-line and scene errors. No rig file is written unless 0.
int calibrateCommand(const CalibrateOptions& options);

void addCalibrateCommand(CommandSet& commands);

}  // namespace uampc::app
