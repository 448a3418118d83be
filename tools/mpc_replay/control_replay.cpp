#include "control_replay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "uampc/mpc/uncertainty_filter.hpp"
#include "uampc/mpc/uncertainty_surrogate.hpp"
#include "uampc/run_files/csv.hpp"

namespace uampc::tools {
namespace {

double rms(const std::vector<double>& v) {
  double sum = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i) sum += (v[i] - v[i - 1]) * (v[i] - v[i - 1]);
  return v.size() > 1 ? std::sqrt(sum / double(v.size() - 1)) : 0.0;
}

}  // namespace

std::vector<ControlRecord> readControlRecords(const std::string& path) {
  // The run files' one CSV reader; the positions of the columns are uncertainty.csv's
  // (run_files::UncertaintyRow), the checks below this tool's.
  const run_files::CsvTable table = run_files::readCsv(path);
  std::vector<ControlRecord> records;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const std::string where = path + ":" + std::to_string(table.lines[i]);
    const std::vector<double>& v = table.rows[i];
    for (const double value : v) {
      if (!std::isfinite(value)) throw std::runtime_error(where + ": a value is not finite");
    }
    if (v.size() < 6)
      throw std::runtime_error(where + ": expected time, theta_start, delta_theta, command and U samples");
    ControlRecord r{v[0], v[1], v[2], v[3], std::vector<double>(v.begin() + 4, v.end())};
    if (!(r.sample_step > 0.0) || std::abs(r.sample_step * double(r.samples.size()) - 2.0 * M_PI) > 1e-6) {
      throw std::runtime_error(where + ": the samples do not cover one turn at delta_theta");
    }
    records.push_back(std::move(r));
  }
  return records;
}

ReplayStats replayControl(const std::vector<ControlRecord>& records, const ReplayOptions& options) {
  mpc::UncertaintyFilter filter(options.filter_weight);  // throws on a weight outside (0, 1]
  if (options.sample_stride < 1) throw std::invalid_argument("sample stride must be at least 1");
  for (const ControlRecord& r : records) {
    if (r.samples.size() % static_cast<std::size_t>(options.sample_stride) != 0) {
      throw std::invalid_argument("sample stride " + std::to_string(options.sample_stride) + " does not divide the " +
                                  std::to_string(r.samples.size()) + " samples of a turn");
    }
  }
  const mpc::MotorMpc mpc(options.mpc);
  ReplayStats stats;
  std::vector<double> recorded;
  for (const ControlRecord& r : records) {
    const std::vector<double> samples = filter.apply(r.theta_start, r.sample_step, r.samples);
    std::vector<double> strided;
    for (std::size_t s = 0; s < samples.size(); s += static_cast<std::size_t>(options.sample_stride)) {
      strided.push_back(samples[s]);
    }
    const mpc::UncertaintySurrogate surrogate(r.theta_start, r.sample_step * options.sample_stride, strided);
    const double previous = stats.commands.empty() ? mpc::MotorMpc::kNoPreviousCommand : stats.commands.back();
    const double command = mpc.solve(surrogate, r.theta_start, previous).speeds.front();
    stats.commands.push_back(command);
    recorded.push_back(r.command);
    stats.max_difference = std::max(stats.max_difference, std::abs(command - r.command));
    stats.replayed_mean += command;
    if (command <= options.mpc.omega_min + 1e-3 || command >= options.mpc.omega_max - 1e-3) stats.at_bounds += 1.0;
  }
  stats.steps = records.size();
  if (stats.steps > 0) {
    stats.replayed_mean /= double(stats.steps);
    stats.at_bounds /= double(stats.steps);
  }
  stats.recorded_change_rms = rms(recorded);
  stats.replayed_change_rms = rms(stats.commands);
  return stats;
}

}  // namespace uampc::tools
