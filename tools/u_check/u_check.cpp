// u_check: U(theta) as the controller predicts it, against what the LO achieves at each motor
// angle (uncertainty_check.hpp says how). A development tool, one process, no DDS.
//
//   u_check (TRAJECTORY.csv | corridor | multilevel | campus) --at T[,T...] [--seed N]
//           [--motor RAD_PER_S] [--warmup S] [--trials N] [--rotation-sigma DEG]
//           [--position-sigma M] [--csv FILE] [--svg PREFIX] [--set GROUP.NAME=VALUE ...]
//
// Prints, per probe time, the LO's own error, the local map's size, the ranges of U and of the
// measured figures, and Spearman's rank correlation of U with the posterior pose-covariance
// trace and with the Monte Carlo mean square registration error; then the means over the
// probes where the LO held. The oracle columns rank the angles by the same criterion computed from
// the information the LO's update really had: how good the criterion is, apart from how well U
// predicts the view. --set takes the components' own parameters, as a scene does:
// controller.NAME the mpc component's (panorama_width, panorama_height, ray_step_deg,
// range_weight_voxel: 0 for the paper's equal rays, ...), world.NAME map_provider's
// (density_profile, corridor_door_spacing, point_map_resolution, ...).
// --csv writes one row per probe and angle; --svg PREFIX draws log U against each measured figure
// (PREFIX_trace.svg, PREFIX_mse.svg), one colour per probe where the LO held.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "mpc_parameters.hpp"
#include "parameter_overrides.hpp"
#include "simulated_lidar.hpp"
#include "tool_main.hpp"
#include "uncertainty_check.hpp"
#include "world_parameters.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/plots/svg_plot.hpp"

using namespace uampc;

namespace {

struct Range {
  double min = INFINITY, max = -INFINITY;
  void add(double v) { min = std::min(min, v), max = std::max(max, v); }
};

void printProbe(const tools::ProbeResult& r) {
  Range u, trace, error;
  for (const auto& a : r.angles) u.add(a.predicted), trace.add(a.posterior_trace), error.add(a.mean_square_error);
  std::printf("%7.1f %8.3f %7.2f %6zu  %9.3g %9.3g  %9.3g %9.3g  %9.3g %9.3g  %7.3f %7.3f  %7.3f %7.3f%s\n", r.time,
              r.lo_position_error, r.lo_rotation_error * 180.0 / M_PI, r.local_map_points, u.min, u.max, trace.min,
              trace.max, error.min, error.max, r.spearman_trace, r.spearman_error, r.spearman_oracle_trace,
              r.spearman_oracle_error, r.lo_lost ? "  LO lost: ignored" : "");
}

// log10 U against log10 of a measured figure, one colour per probe (the figures of
// docs/results/u-check.md, in docs/results/figures/).
void writeFigure(const std::string& path, const std::string& source, const std::vector<tools::ProbeResult>& probes,
                 bool posterior_trace) {
  app::svg::LinePlot plot;
  plot.title = source + ": U against the LO's " +
               (posterior_trace ? "posterior pose covariance" : "Monte Carlo registration error");
  plot.x_label = "log10 U (predicted, controller)";
  plot.y_label = posterior_trace ? "log10 trace of posterior pose covariance" : "log10 mean square error";
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const tools::ProbeResult& r = probes[i];
    app::svg::Series series;
    char label[96];
    std::snprintf(label, sizeof label, "t = %.1f s, Spearman %.2f", r.time,
                  posterior_trace ? r.spearman_trace : r.spearman_error);
    series.label = label;
    series.points = true;
    series.width = 2.5;
    series.colour = app::svg::paletteColour(i);
    for (const auto& a : r.angles) {
      series.x.push_back(std::log10(a.predicted));
      series.y.push_back(std::log10(posterior_trace ? a.posterior_trace : a.mean_square_error));
    }
    plot.series.push_back(series);
  }
  FILE* file = std::fopen(path.c_str(), "w");
  if (!file) throw std::runtime_error("cannot write " + path);
  const std::string svg = app::svg::render(plot);
  std::fwrite(svg.data(), 1, svg.size(), file);
  std::fclose(file);
}

int run(int argc, char** argv) {
  CLI::App app{"U(theta) as the controller predicts it, against what the LO achieves at each motor angle.", "u_check"};
  std::string source, csv_path, svg_prefix;
  std::vector<double> times;
  std::uint64_t seed = 1;
  double rotation_sigma_deg = 0.0;
  std::vector<std::string> assignments;
  tools::UncertaintyCheckConfig config;
  rotation_sigma_deg = config.start_rotation_sigma * 180.0 / M_PI;
  app.add_option("SOURCE", source, "an MCD trajectory (.csv), or corridor, multilevel or campus")->required();
  app.add_option("--at", times, "probe times, s (T[,T...])")
      ->required()
      ->delimiter(',')
      ->check(command_line::kFiniteNonNegative);
  app.add_option("--seed", seed, "the world's and the trials' seed")->capture_default_str();
  app.add_option("--motor", config.motor_speed, "motor speed before the probes, rad/s")
      ->check(command_line::kFinite)
      ->capture_default_str();
  app.add_option("--warmup", config.warmup, "s the LO runs before each probe")
      ->check(command_line::kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--trials", config.trials, "Monte Carlo registrations per angle")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--rotation-sigma", rotation_sigma_deg, "start rotation error of the trials, degrees (1 sigma)")
      ->check(command_line::kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--position-sigma", config.start_position_sigma, "start position error of the trials, m (1 sigma)")
      ->check(command_line::kFiniteNonNegative)
      ->capture_default_str();
  app.add_option("--csv", csv_path, "write one row per probe and angle to FILE");
  app.add_option("--svg", svg_prefix, "draw log U against each measured figure: PREFIX_trace.svg, PREFIX_mse.svg");
  app.add_option("--set", assignments,
                 "a component's parameter, as in a scene: controller.NAME (mpc) or world.NAME (map_provider)")
      ->type_name(tools::ParameterOverrides::kSyntax);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  world::WorldSettings settings = tools::worldSettingsFor(source);
  settings.seed = config.seed = seed;
  config.start_rotation_sigma = rotation_sigma_deg * M_PI / 180.0;
  try {
    tools::ParameterOverrides set(assignments);
    set.apply("controller", bindMpcParameters, config.controller);
    set.apply("world", bindWorldParameters, settings);
    set.checkAllUsed();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "u_check: %s\n", e.what());
    return 2;
  }

  const world::World world = world::buildWorld(settings);
  tools::UncertaintyCheck check(world, config);
  FILE* csv = nullptr;
  if (!csv_path.empty()) {
    csv = std::fopen(csv_path.c_str(), "w");
    if (!csv) throw std::runtime_error("cannot write " + csv_path);
    std::fprintf(csv,
                 "time,theta_deg,predicted_u,oracle_u,posterior_trace,mean_square_error,rms_rotation_deg,rms_position_"
                 "m,correspondences\n");
  }
  std::printf("# source %s, motor %.2f rad/s before the probes, %d trials, start sigma %.2f deg / %.3f m\n", source.c_str(),
              config.motor_speed, config.trials, config.start_rotation_sigma * 180.0 / M_PI,
              config.start_position_sigma);
  std::printf(
      "#     t  lo_err_m lo_deg  map_pts    U_min     U_max   trace_min trace_max    mse_min   mse_max  rho_tr  "
      "rho_mse  orc_tr  orc_mse\n");
  double sum_trace = 0.0, sum_error = 0.0, sum_oracle_trace = 0.0, sum_oracle_error = 0.0;
  int held = 0;
  std::vector<tools::ProbeResult> probes;  // where the LO held, for the figures
  for (double t : times) {
    if (t + 1.0 > world.trajectory.endTime()) {
      std::printf("# %.1f s skipped: the path ends at %.1f s\n", t, world.trajectory.endTime());
      continue;
    }
    const tools::ProbeResult r = check.probe(t);
    if (!r.lo_lost) probes.push_back(r);
    printProbe(r);
    std::fflush(stdout);
    if (!r.lo_lost && std::isfinite(r.spearman_trace) && std::isfinite(r.spearman_error)) {
      sum_trace += r.spearman_trace, sum_error += r.spearman_error, ++held;
      sum_oracle_trace += r.spearman_oracle_trace, sum_oracle_error += r.spearman_oracle_error;
    }
    for (const auto& a : r.angles) {
      if (csv) {
        std::fprintf(csv, "%.3f,%.1f,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f,%zu\n", r.time, a.theta * 180.0 / M_PI, a.predicted,
                     a.oracle, a.posterior_trace, a.mean_square_error, a.rms_rotation * 180.0 / M_PI, a.rms_position,
                     a.correspondences);
      }
    }
  }
  if (csv) std::fclose(csv);
  if (!svg_prefix.empty()) {
    writeFigure(svg_prefix + "_trace.svg", source, probes, true);
    writeFigure(svg_prefix + "_mse.svg", source, probes, false);
  }
  if (held > 0) {
    std::printf(
        "summary: %s, %d of %zu probes held: mean Spearman(U, trace) %.3f, (U, mse) %.3f; oracle: (trace) %.3f, (mse) "
        "%.3f\n",
        source.c_str(), held, times.size(), sum_trace / held, sum_error / held, sum_oracle_trace / held,
        sum_oracle_error / held);
  } else {
    std::printf("summary: %s, no probe where the LO held\n", source.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return uampc::tools::runTool("u_check", run, argc, argv); }
