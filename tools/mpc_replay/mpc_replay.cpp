// mpc_replay: UA-MPC's recorded control steps (a run's uncertainty.csv) solved again with other
// options (control_replay.hpp). A development tool.
//
//   mpc_replay RUN_DIR/uncertainty.csv [--sample-stride K] [--set controller.NAME=VALUE ...]
//
// --set takes the mpc component's own parameters with their bounds (alpha, beta, horizon,
// horizon_dt, omega_min, omega_max, u_filter_weight, ...; mpc_parameters.hpp). Prints the steps,
// the recorded and replayed command change per step (RMS), the replayed mean command, the share of
// steps at the speed bounds, and the largest difference from the recorded commands (0 with the
// run's own options: the solve is deterministic).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "control_replay.hpp"
#include "mpc_parameters.hpp"
#include "parameter_overrides.hpp"
#include "tool_main.hpp"

using namespace uampc;

namespace {

int run(int argc, char** argv) {
  CLI::App app{"Solves a UA-MPC run's recorded control steps again with other options, open loop.", "mpc_replay"};
  std::string file;
  int sample_stride = 1;
  std::vector<std::string> assignments;
  app.add_option("UNCERTAINTY_CSV", file, "a run's uncertainty.csv")->required();
  app.add_option("--sample-stride", sample_stride,
                 "use every K-th recorded U sample only (a coarser delta_theta from the same samples)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--set", assignments, "the controller's parameter, as in a scene: controller.NAME")
      ->type_name(tools::ParameterOverrides::kSyntax);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  mpc::UaMpcController::Config controller;  // the mpc component's defaults
  try {
    tools::ParameterOverrides set(assignments);
    set.apply("controller", bindMpcParameters, controller);
    set.checkAllUsed();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mpc_replay: %s\n", e.what());
    return 2;
  }
  tools::ReplayOptions options;
  options.mpc = controller.mpc;
  options.filter_weight = controller.u_filter_weight;
  options.sample_stride = sample_stride;
  const tools::ReplayStats s = tools::replayControl(tools::readControlRecords(file), options);
  std::printf(
      "steps %zu  recorded change rms %.3f rad/s  replayed change rms %.3f rad/s  mean %.3f rad/s  "
      "at bounds %.1f %%  max |replayed - recorded| %.3g rad/s\n",
      s.steps, s.recorded_change_rms, s.replayed_change_rms, s.replayed_mean, 100.0 * s.at_bounds, s.max_difference);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return uampc::tools::runTool("mpc_replay", run, argc, argv); }
