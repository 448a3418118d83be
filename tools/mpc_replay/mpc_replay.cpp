// mpc_replay: UA-MPC's recorded control steps (a run's uncertainty.csv) solved again with other
// options (control_replay.hpp). A development tool.
//
//   mpc_replay RUN_DIR/uncertainty.csv [--alpha A] [--beta B] [--horizon M] [--horizon-dt S]
//              [--filter W] [--sample-stride K]
//
// Prints the steps, the recorded and replayed command change per step (RMS), the replayed mean
// command, the share of steps at the speed bounds, and the largest difference from the recorded
// commands (0 with the run's own options: the solve is deterministic).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "control_replay.hpp"
#include "tool_main.hpp"

using namespace uampc;

namespace {

int run(int argc, char** argv) {
  if (argc < 2 || argc % 2 != 0 || std::string(argv[1]) == "--help") {
    std::fprintf(stderr,
                 "usage: mpc_replay RUN_DIR/uncertainty.csv [--alpha A] [--beta B] [--horizon M] [--horizon-dt S] "
                 "[--filter W] [--sample-stride K]\n");
    return argc >= 2 && std::string(argv[1]) == "--help" ? 0 : 2;
  }
  tools::ReplayOptions options;  // the mpc component's defaults
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const double v = tools::number(flag, argv[i + 1]);
    if (flag == "--alpha")
      options.mpc.alpha = v;
    else if (flag == "--beta")
      options.mpc.beta = v;
    else if (flag == "--horizon")
      options.mpc.horizon = static_cast<int>(v);
    else if (flag == "--horizon-dt")
      options.mpc.dt = v;
    else if (flag == "--sample-stride")
      options.sample_stride = static_cast<int>(v);
    else if (flag == "--filter")
      options.filter_weight = v;
    else
      throw std::invalid_argument("unknown option " + flag);
  }
  const tools::ReplayStats s = tools::replayControl(tools::readControlRecords(argv[1]), options);
  std::printf(
      "steps %zu  recorded change rms %.3f rad/s  replayed change rms %.3f rad/s  mean %.3f rad/s  "
      "at bounds %.1f %%  max |replayed - recorded| %.3g rad/s\n",
      s.steps, s.recorded_change_rms, s.replayed_change_rms, s.replayed_mean, 100.0 * s.at_bounds, s.max_difference);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return uampc::tools::runTool("mpc_replay", run, argc, argv); }
