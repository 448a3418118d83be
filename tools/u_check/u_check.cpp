// u_check: U(theta) as the controller predicts it, against what the LO achieves at each motor
// angle (uncertainty_check.hpp says how). A development tool, one process, no DDS.
//
//   u_check (TRAJECTORY.csv | corridor | multilevel | campus) --at T[,T...] [--seed N]
//           [--motor RAD_PER_S] [--warmup S] [--trials N] [--rotation-sigma DEG]
//           [--position-sigma M] [--door-spacing M] [--profile P] [--open-fraction F] [--panorama WxH] [--ray-step DEG]
//           [--range-weight-voxel M] [--csv FILE]
//
// Prints, per probe time, the LO's own error, the local map's size, the ranges of U and of the
// measured figures, and Spearman's rank correlation of U with the posterior pose-covariance
// trace and with the Monte Carlo mean square registration error; then the means over the
// probes where the LO held. The oracle columns rank the angles by the same criterion computed from
// the information the LO's update really had: how good the criterion is, apart from how well U
// predicts the view. --panorama and --ray-step change U's depth map and ray grid (defaults: the
// mpc component's); --range-weight-voxel is the mpc component's range_weight_voxel (0: the
// paper's equal rays).
// --csv writes one row per probe and angle; --svg PREFIX draws log U against each measured figure
// (PREFIX_trace.svg, PREFIX_mse.svg), one colour per probe where the LO held.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "simulated_lidar.hpp"
#include "uampc/plots/svg_plot.hpp"
#include "tool_main.hpp"
#include "uncertainty_check.hpp"

using namespace uampc;

namespace {

constexpr const char* kUsage =
    "usage: u_check (TRAJECTORY.csv | corridor | multilevel | campus) --at T[,T...] [--seed N] "
    "[--motor RAD_PER_S] [--warmup S] [--trials N] [--rotation-sigma DEG] [--position-sigma M] "
    "[--door-spacing M] [--profile P] [--open-fraction F] [--panorama WxH] [--ray-step DEG] [--range-weight-voxel M] "
    "[--csv FILE] [--svg PREFIX]\n";

std::vector<double> numberList(const std::string& flag, const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) values.push_back(tools::number(flag, item));
  if (values.empty()) throw std::invalid_argument(flag + ": no times given");
  return values;
}

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
  if (argc < 2 || argc % 2 != 0 || std::string(argv[1]) == "--help") {
    std::fprintf(stderr, "%s", kUsage);
    return argc >= 2 && std::string(argv[1]) == "--help" ? 0 : 2;
  }
  world::WorldSettings settings = tools::worldSettingsFor(argv[1]);
  tools::UncertaintyCheckConfig config;
  std::vector<double> times;
  std::string csv_path;
  std::string svg_prefix;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--at")
      times = numberList(flag, value);
    else if (flag == "--seed")
      settings.seed = config.seed = static_cast<std::uint64_t>(tools::number(flag, value));
    else if (flag == "--motor")
      config.motor_speed = tools::number(flag, value);
    else if (flag == "--warmup")
      config.warmup = tools::number(flag, value);
    else if (flag == "--trials")
      config.trials = tools::count(flag, value);
    else if (flag == "--rotation-sigma")
      config.start_rotation_sigma = tools::number(flag, value) * M_PI / 180.0;
    else if (flag == "--position-sigma")
      config.start_position_sigma = tools::number(flag, value);
    else if (flag == "--door-spacing")
      settings.corridor_door_spacing = tools::number(flag, value);
    else if (flag == "--profile")
      settings.density_profile = value;
    else if (flag == "--open-fraction")
      settings.open_fraction = tools::number(flag, value);
    else if (flag == "--csv")
      csv_path = value;
    else if (flag == "--svg")
      svg_prefix = value;
    else if (flag == "--range-weight-voxel")
      config.controller.range_weight_voxel = tools::number(flag, value);
    else if (flag == "--ray-step") {
      config.controller.uncertainty.azimuth_step = config.controller.uncertainty.elevation_step =
          tools::number(flag, value) * M_PI / 180.0;
    } else if (flag == "--panorama") {
      const auto x = value.find('x');
      if (x == std::string::npos) throw std::invalid_argument("--panorama: expected WxH, e.g. 180x90");
      config.controller.depth_map.width = tools::count(flag, value.substr(0, x));
      config.controller.depth_map.height = tools::count(flag, value.substr(x + 1));
    } else
      throw std::invalid_argument("unknown option " + flag + "\n" + kUsage);
  }
  if (times.empty()) throw std::invalid_argument(std::string("--at is required\n") + kUsage);

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
  std::printf("# source %s, motor %.2f rad/s before the probes, %d trials, start sigma %.2f deg / %.3f m\n", argv[1],
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
    writeFigure(svg_prefix + "_trace.svg", argv[1], probes, true);
    writeFigure(svg_prefix + "_mse.svg", argv[1], probes, false);
  }
  if (held > 0) {
    std::printf(
        "summary: %s, %d of %zu probes held: mean Spearman(U, trace) %.3f, (U, mse) %.3f; oracle: (trace) %.3f, (mse) "
        "%.3f\n",
        argv[1], held, times.size(), sum_trace / held, sum_error / held, sum_oracle_trace / held,
        sum_oracle_error / held);
  } else {
    std::printf("summary: %s, no probe where the LO held\n", argv[1]);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return uampc::tools::runTool("u_check", run, argc, argv); }
