#include "report/results_table.hpp"

#include <cmath>
#include <cstdio>

#include "report/experiment_statistics.hpp"

namespace uampc::app {

namespace {

std::string withCount(std::string text, const MeanOverSeeds& cell, int seeds) {
  if (cell.runs < seeds) text += " (" + std::to_string(cell.runs) + "/" + std::to_string(seeds) + ")";
  return text;
}

std::string percentChange(double ratio) {
  const double percent = (ratio - 1.0) * 100.0;
  return (percent >= 0 ? "+" : "") + fixed(percent, 1) + "%";
}

int indexOf(const std::vector<std::string>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

// "Losses of track" table: lost / finished runs per controller and scene.
std::string lossesOfTrack(const ResultsTable& t) {
  std::string md =
      "## Losses of track\n\nRuns that lost track (the estimated speed more than 1 m/s off the true one over 1 s, "
      "at some point; when, in the Runs table) of the finished runs; \"at start-up\": lost within the first " +
      std::to_string(static_cast<int>(kStartUpLossWindowS)) +
      " s, where the LO's first map, not the controller, decides (docs/decisions/start-hold.md); \"recovered\": held, "
      "but with velocity resets of the LO (docs/decisions/lo-velocity-reset.md).\n\n| controller |";
  for (const auto& s : t.scenes) md += " " + s + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < t.scenes.size(); ++i) md += "---|";
  md += "\n";
  for (std::size_t c = 0; c < t.controllers.size(); ++c) {
    md += "| " + t.controllers[c] + " |";
    for (std::size_t s = 0; s < t.scenes.size(); ++s) {
      const int start_up = t.start_up_lost_runs[c][s], recovered = t.recovered_runs[c][s];
      md += " " + std::to_string(t.lost_runs[c][s]) + " lost of " + std::to_string(t.finished_runs[c][s]) +
            (start_up > 0 ? " (" + std::to_string(start_up) + " at start-up)" : "") +
            (recovered > 0 ? ", " + std::to_string(recovered) + " recovered" : "") + " |";
    }
    md += "\n";
  }
  return md;
}

}  // namespace

ResultsTable summarize(const Experiment& experiment, const std::vector<RunResult>& results) {
  ResultsTable t;
  t.scenes = sceneNames(experiment);
  t.controllers = controllerNames(experiment);
  t.seeds = static_cast<int>(experiment.seeds.size());
  t.subject = experiment.subject;
  t.baseline = experiment.baseline;
  t.subject_index = indexOf(t.controllers, t.subject);
  t.baseline_index = indexOf(t.controllers, t.baseline);
  const std::size_t nc = t.controllers.size(), ns = t.scenes.size();
  t.ate.assign(nc, std::vector<MeanOverSeeds>(ns));
  t.cmplt.assign(nc, std::vector<MeanOverSeeds>(ns));
  std::vector<std::vector<double>> ate_sum(nc, std::vector<double>(ns, 0.0)), cmplt_sum = ate_sum;
  t.finished_runs.assign(nc, std::vector<int>(ns, 0));
  t.lost_runs = t.finished_runs;
  t.start_up_lost_runs = t.finished_runs;
  t.recovered_runs = t.finished_runs;
  for (const RunResult& r : results) {
    const int c = indexOf(t.controllers, r.controller), s = indexOf(t.scenes, r.scene);
    if (c < 0 || s < 0 || !r.finished()) continue;
    ++t.finished_runs[c][s];
    if (std::isfinite(r.metrics.runaway_time_s)) ++t.lost_runs[c][s];
    if (r.metrics.runaway_time_s <= kStartUpLossWindowS) ++t.start_up_lost_runs[c][s];
    if (!std::isfinite(r.metrics.runaway_time_s) && r.metrics.velocity_resets > 0) ++t.recovered_runs[c][s];
    if (std::isfinite(r.metrics.ate_m)) {
      ate_sum[c][s] += r.metrics.ate_m;
      ++t.ate[c][s].runs;
    }
    if (std::isfinite(r.metrics.cmplt)) {
      cmplt_sum[c][s] += r.metrics.cmplt;
      ++t.cmplt[c][s].runs;
    }
  }
  t.ate_sum.assign(nc, 0.0);
  for (std::size_t c = 0; c < nc; ++c) {
    for (std::size_t s = 0; s < ns; ++s) {
      if (t.ate[c][s].runs) t.ate[c][s].mean = ate_sum[c][s] / t.ate[c][s].runs;
      if (t.cmplt[c][s].runs) t.cmplt[c][s].mean = cmplt_sum[c][s] / t.cmplt[c][s].runs;
      t.ate_sum[c] += t.ate[c][s].mean;  // NaN propagates: a sum with a scene missing is no sum
    }
  }
  t.ate_sum_ratio.assign(nc, kMissing);
  t.cmplt_ratio.assign(nc, std::vector<double>(ns, kMissing));
  if (t.baseline_index >= 0) {
    const auto b = static_cast<std::size_t>(t.baseline_index);
    for (std::size_t c = 0; c < nc; ++c) {
      t.ate_sum_ratio[c] = t.ate_sum[c] / t.ate_sum[b];
      for (std::size_t s = 0; s < ns; ++s) t.cmplt_ratio[c][s] = t.cmplt[c][s].mean / t.cmplt[b][s].mean;
    }
  }
  return t;
}

std::string formatAte(const MeanOverSeeds& cell, int seeds) {
  return std::isfinite(cell.mean) ? withCount(fixed(cell.mean, 2), cell, seeds) : "n/a";
}

std::string formatCmplt(const MeanOverSeeds& cell, int seeds) {
  return std::isfinite(cell.mean) ? withCount(fixed(cell.mean, 0), cell, seeds) : "n/a";
}

std::string formatRatio(double ratio) { return std::isfinite(ratio) ? fixed(ratio, 2) : "n/a"; }

std::string headline(const ResultsTable& t) {
  if (t.subject_index < 0 || t.baseline_index < 0 || t.subject_index == t.baseline_index) return "";
  const auto c = static_cast<std::size_t>(t.subject_index);
  std::string text = t.subject + " against " + t.baseline + ": ATE summed over scenes ";
  text += std::isfinite(t.ate_sum_ratio[c]) ? percentChange(t.ate_sum_ratio[c]) : std::string("n/a");
  text += " (the paper: more than 60% lower); CMPLT";
  for (std::size_t s = 0; s < t.scenes.size(); ++s) {
    text += (s ? ", " : " ") + t.scenes[s] + " " +
            (std::isfinite(t.cmplt_ratio[c][s]) ? percentChange(t.cmplt_ratio[c][s]) : std::string("n/a"));
  }
  return text + " (the paper: less than 2% lower).";
}

std::string renderMarkdown(const Experiment& experiment, const ResultsTable& t, const std::vector<RunResult>& results) {
  std::string md = "# Experiment " + experiment.name + "\n\n";
  md += "From `" + experiment.file + "`: " + std::to_string(t.scenes.size()) + " scene(s) x " +
        std::to_string(t.controllers.size()) + " controller(s) x " + std::to_string(t.seeds) +
        " seed(s). Means over seeds; \"(k/n)\" marks cells where only k of n seeds gave the figure. "
        "ATE: RMSE of the unaligned positions, m. CMPLT: 0.5 m voxels scanned per 5 s window (n/a: "
        "no complete window).\n\n";
  md += "| controller |";
  for (const auto& s : t.scenes) md += " " + s + " ATE m | " + s + " CMPLT |";
  md += " ATE sum m | ATE sum / " + t.baseline + " |";
  for (const auto& s : t.scenes) md += " " + s + " CMPLT / " + t.baseline + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < t.scenes.size() * 3 + 2; ++i) md += "---|";
  md += "\n";
  for (std::size_t c = 0; c < t.controllers.size(); ++c) {
    md += "| " + t.controllers[c] + " |";
    for (std::size_t s = 0; s < t.scenes.size(); ++s) {
      md += " " + formatAte(t.ate[c][s], t.seeds) + " | " + formatCmplt(t.cmplt[c][s], t.seeds) + " |";
    }
    md += " " + (std::isfinite(t.ate_sum[c]) ? fixed(t.ate_sum[c], 2) : std::string("n/a")) + " | " +
          formatRatio(t.ate_sum_ratio[c]) + " |";
    for (std::size_t s = 0; s < t.scenes.size(); ++s) md += " " + formatRatio(t.cmplt_ratio[c][s]) + " |";
    md += "\n";
  }
  const std::string line = headline(t);
  md += "\n" +
        (line.empty() ? "No comparison: the experiment lacks controller '" + t.subject + "' or '" + t.baseline +
                            "' (set compare: {subject, baseline})."
                      : line) +
        "\n\n" + lossesOfTrack(t) + "\n" + statisticsMarkdown(computeStatistics(experiment, results)) +
        "\n## Runs\n\n| scene | controller | seed | status | ATE m | aligned ATE m | CMPLT | CMPLT (ground truth) "
        "| mean speed rad/s | lost track at s | sim s | wall s | real-time factor | directory |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto num = [](double v, int decimals) { return std::isfinite(v) ? fixed(v, decimals) : std::string("n/a"); };
  for (const RunResult& r : results) {
    md += "| " + r.scene + " | " + r.controller + " | " + std::to_string(r.seed) + " | " + statusName(r.status) +
          (r.failure.empty() ? "" : ": " + r.failure) + " | " + num(r.metrics.ate_m, 3) + " | " +
          num(r.metrics.ate_aligned_m, 3) + " | " + num(r.metrics.cmplt, 0) + " | " +
          num(r.metrics.cmplt_ground_truth, 0) + " | " + num(r.metrics.mean_speed, 2) + " | " +
          (std::isfinite(r.metrics.runaway_time_s) ? fixed(r.metrics.runaway_time_s, 1) : std::string("never")) +
          " | " + num(r.metrics.sim_time_s, 1) + " | " + num(r.wall_time_s, 1) + " | " + num(r.real_time_factor, 2) +
          " | " + r.directory + " |\n";
  }
  return md;
}

}  // namespace uampc::app
