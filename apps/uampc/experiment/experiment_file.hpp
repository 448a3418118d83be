// An experiment: the paper's evaluation as one YAML file (docs/dev/architecture.md section 1). It
// names scenes, controllers and seeds; `uampc experiment` runs every combination with
// `uampc launch`.
//
//   name: paper_table              # optional; defaults to the file name
//   duration: 60                   # optional: s of sim time per run (--set clock.duration)
//   seeds: [1, 2, 3]               # optional; default [1]; each run gets --set seed=K
//   compare: {subject: ua_mpc, baseline: constant_3.6}   # optional; the ratios of results.md
//   scenes:
//     - name: campus               # letters, digits, _ . - (it names a directory)
//       scene: ../scenes/campus_ua_mpc.yaml   # relative to this file
//       overrides: [world.path_laps=2, "world.trajectory_file=${data_dir}/ntu_day01.csv"]
//   controllers:                   # optional; default: ua_mpc, constant_1.8/3.6/7.2, zero
//     - name: ua_mpc
//       overrides: [controller.mode=ua_mpc]
//
// Overrides are `uampc launch --set` texts. ${data_dir} is replaced by --data-dir (absolute).
// seed and domain_id belong to the experiment and may not be overridden.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace uampc::app {

// Every problem found in an experiment file, each "file:line:column: error: message".
class ExperimentError : public std::runtime_error {
 public:
  explicit ExperimentError(std::vector<std::string> messages);
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  std::vector<std::string> messages_;
};

struct ExperimentScene {
  std::string name;
  std::string scene_file;              // absolute
  std::vector<std::string> overrides;  // NAME=VALUE, variables substituted
  std::string location;                // file:line:column of the entry, for later messages
};

struct ExperimentController {
  std::string name;
  std::vector<std::string> overrides;
  std::string location;
};

struct Experiment {
  std::string file;  // absolute
  std::string name;
  std::optional<double> duration_s;
  std::vector<std::uint64_t> seeds{1};
  std::vector<ExperimentScene> scenes;
  std::vector<ExperimentController> controllers;
  std::string subject = "ua_mpc";         // the controller under test
  std::string baseline = "constant_3.6";  // the paper's constant-speed baseline
};

// The scenes' and controllers' names, in the file's order (the rows and columns of every table).
std::vector<std::string> sceneNames(const Experiment& experiment);
std::vector<std::string> controllerNames(const Experiment& experiment);

// The paper's comparison: UA-MPC, constant speed at half, once and twice omega_pre, zero speed.
std::vector<ExperimentController> defaultControllers();

// Reads and validates an experiment file; `variables` maps names usable as ${name} in scene
// paths and overrides (data_dir). Throws ExperimentError listing every problem.
Experiment loadExperiment(const std::string& path, const std::map<std::string, std::string>& variables);

}  // namespace uampc::app
