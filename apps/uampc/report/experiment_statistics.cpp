#include "report/experiment_statistics.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "uampc/run_files/json_text.hpp"

namespace uampc::app {

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  return buffer;
}

namespace {

bool lostTrack(const RunResult& r) { return std::isfinite(r.metrics.runaway_time_s); }

CellStatistics cellOf(const std::vector<const RunResult*>& runs) {
  CellStatistics cell;
  std::vector<double> ates, percents, cmplts;
  for (const RunResult* r : runs) {
    ++cell.runs;
    ++(lostTrack(*r) ? cell.lost : cell.held);
    if (std::isfinite(r->metrics.ate_m)) {
      ates.push_back(r->metrics.ate_m);
      if (r->metrics.distance_m > 0) percents.push_back(100.0 * r->metrics.ate_m / r->metrics.distance_m);
    }
    if (std::isfinite(r->metrics.cmplt)) cmplts.push_back(r->metrics.cmplt);
  }
  cell.median_ate_m = median(ates);
  double sum = 0.0;
  for (double a : ates) sum += a;
  cell.mean_ate_m = ates.empty() ? kMissing : sum / ates.size();
  cell.median_ate_percent = median(percents);
  cell.median_cmplt = median(cmplts);
  return cell;
}

RunPair pairOf(const RunResult& subject, const RunResult& baseline) {
  return {subject.metrics.ate_m,  baseline.metrics.ate_m, subject.metrics.cmplt,
          baseline.metrics.cmplt, lostTrack(subject),     lostTrack(baseline)};
}

// p with three significant digits (0.0625, 0.00012), since its size matters more than its decimals.
std::string pText(double p) {
  if (!std::isfinite(p)) return "n/a";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3g", p);
  return buffer;
}

std::string testText(const WilcoxonResult& w) {
  if (w.n == 0) return "no non-zero difference";
  std::string text = std::string(w.exact ? "exact" : "normal approx.") + ", n=" + std::to_string(w.n);
  if (w.zeros_dropped) text += " (" + std::to_string(w.zeros_dropped) + " zero difference(s) dropped)";
  return text;
}

std::vector<std::string> comparisonRow(const std::string& controller, const std::string& scene,
                                       const PairedComparison& c) {
  const std::string lower =
      c.pairs ? std::to_string(static_cast<int>(std::lround(c.fraction_subject_lower * c.pairs))) + "/" +
                    std::to_string(c.pairs) + " (" + fixed(100.0 * c.fraction_subject_lower, 0) + "%)"
              : "n/a";
  return {controller,
          scene,
          std::to_string(c.pairs),
          fixed(c.median_ate_ratio, 2),
          fixed(c.summed_ate_ratio, 2),
          lower,
          std::to_string(c.subject_lost),
          std::to_string(c.baseline_lost),
          fixed(c.median_cmplt_ratio, 2),
          pText(c.wilcoxon.p_value),
          testText(c.wilcoxon)};
}

std::string markdownRow(const std::vector<std::string>& cells) {
  std::string row = "|";
  for (const auto& cell : cells) row += " " + cell + " |";
  return row + "\n";
}

std::string markdownTable(const TextTable& table, std::size_t bold_column) {
  std::string md = markdownRow(table.header) + "|";
  for (std::size_t i = 0; i < table.header.size(); ++i) md += "---|";
  md += "\n";
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    std::vector<std::string> cells = table.rows[r];
    if (table.emphasised[r]) cells[bold_column] = "**" + cells[bold_column] + "**";
    md += markdownRow(cells);
  }
  return md;
}

run_files::Json cellJson(const CellStatistics& c) {
  return {{"runs", c.runs},
          {"held", c.held},
          {"lost", c.lost},
          {"median_ate_m", c.median_ate_m},
          {"mean_ate_m", c.mean_ate_m},
          {"median_ate_percent_of_distance", c.median_ate_percent},
          {"median_cmplt", c.median_cmplt}};
}

run_files::Json comparisonJson(const PairedComparison& c) {
  const run_files::Json wilcoxon = {{"n", c.wilcoxon.n},
                                    {"zeros_dropped", c.wilcoxon.zeros_dropped},
                                    {"w_plus", c.wilcoxon.w_plus},
                                    {"p_two_sided", c.wilcoxon.p_value},
                                    {"exact", c.wilcoxon.exact}};
  return {{"pairs", c.pairs},
          {"median_ate_ratio", c.median_ate_ratio},
          {"summed_ate_ratio", c.summed_ate_ratio},
          {"fraction_subject_lower", c.fraction_subject_lower},
          {"subject_lost", c.subject_lost},
          {"baseline_lost", c.baseline_lost},
          {"median_cmplt_ratio", c.median_cmplt_ratio},
          {"wilcoxon_signed_rank", wilcoxon}};
}

}  // namespace

ExperimentStatistics computeStatistics(const Experiment& experiment, const std::vector<RunResult>& results) {
  ExperimentStatistics st;
  st.scenes = sceneNames(experiment);
  st.controllers = controllerNames(experiment);
  // Finished runs by (scene, controller, seed): the pairing key.
  std::map<std::tuple<std::string, std::string, std::uint64_t>, const RunResult*> finished;
  for (const RunResult& r : results) {
    if (r.finished()) finished[{r.scene, r.controller, r.seed}] = &r;
  }
  for (const auto& controller : st.controllers) {
    st.cells.emplace_back();
    for (const auto& scene : st.scenes) {
      std::vector<const RunResult*> runs;
      for (auto seed : experiment.seeds) {
        if (auto it = finished.find({scene, controller, seed}); it != finished.end()) runs.push_back(it->second);
      }
      st.cells.back().push_back(cellOf(runs));
    }
  }
  bool has_subject = false;
  for (const auto& c : st.controllers) has_subject = has_subject || c == experiment.subject;
  if (!has_subject) return st;
  st.subject = experiment.subject;
  for (const auto& controller : st.controllers) {
    if (controller == st.subject) continue;
    BaselineComparison comparison{controller, {}, {}};
    std::vector<RunPair> pooled;
    for (const auto& scene : st.scenes) {
      std::vector<RunPair> pairs;
      for (auto seed : experiment.seeds) {
        const auto subject = finished.find({scene, st.subject, seed});
        const auto baseline = finished.find({scene, controller, seed});
        if (subject == finished.end() || baseline == finished.end()) continue;
        if (!std::isfinite(subject->second->metrics.ate_m) || !std::isfinite(baseline->second->metrics.ate_m)) continue;
        pairs.push_back(pairOf(*subject->second, *baseline->second));
      }
      pooled.insert(pooled.end(), pairs.begin(), pairs.end());
      comparison.per_scene.push_back(comparePairs(pairs));
    }
    comparison.pooled = comparePairs(pooled);
    st.comparisons.push_back(std::move(comparison));
  }
  return st;
}

TextTable cellTable(const ExperimentStatistics& st) {
  TextTable t;
  t.header = {"scene",      "controller",        "runs",        "held", "lost", "median ATE m",
              "mean ATE m", "ATE % of distance", "median CMPLT"};
  for (std::size_t s = 0; s < st.scenes.size(); ++s) {
    for (std::size_t c = 0; c < st.controllers.size(); ++c) {
      const CellStatistics& cell = st.cells[c][s];
      t.rows.push_back({st.scenes[s], st.controllers[c], std::to_string(cell.runs), std::to_string(cell.held),
                        std::to_string(cell.lost), fixed(cell.median_ate_m, 2), fixed(cell.mean_ate_m, 2),
                        fixed(cell.median_ate_percent, 2), fixed(cell.median_cmplt, 0)});
      t.emphasised.push_back(false);
    }
  }
  return t;
}

TextTable comparisonTable(const ExperimentStatistics& st) {
  TextTable t;
  if (st.subject.empty()) return t;
  const std::string& u = st.subject;
  t.header = {"against",    "scene",     "pairs",      "ATE ratio, median of pairs",   "ATE ratio, sums",
              u + " lower", u + " lost", "other lost", "CMPLT ratio, median of pairs", "p",
              "test"};
  for (const BaselineComparison& b : st.comparisons) {
    for (std::size_t s = 0; s < st.scenes.size(); ++s) {
      t.rows.push_back(comparisonRow(b.controller, st.scenes[s], b.per_scene[s]));
      t.emphasised.push_back(false);
    }
    t.rows.push_back(comparisonRow(b.controller, "all scenes", b.pooled));
    t.emphasised.push_back(true);
  }
  return t;
}

std::string cellTableExplanation() {
  return "Finished runs; held: never lost track; ATE % of distance: median over runs of the ATE over the ground "
         "truth's path length; medians are not moved by one run that ran away.";
}

std::string comparisonExplanation(const std::string& u) {
  return u + "'s runs paired with each other controller's by scene and seed (both finished with an ATE). Ratios are " +
         u + " / the other: the median of the per-pair ATE ratios, the sum of " + u +
         "'s ATE over the sum of the other's, the median of the per-pair CMPLT ratios. p: two-sided Wilcoxon "
         "signed-rank test on the paired ATE differences; zero differences are dropped (Wilcoxon's convention); "
         "exact distribution for n <= 25 without ties, else the normal approximation with tie and continuity "
         "correction.";
}

const char* const kFewPairsNote =
    "With n pairs the smallest possible two-sided p is 2/2^n: 0.0625 with 5 pairs (5 seeds on one scene), which is "
    "why the pooled line (all scenes) matters.";

std::string statisticsMarkdown(const ExperimentStatistics& st) {
  std::string md = "## Per scene and controller\n\n" + cellTableExplanation() + "\n\n" +
                   markdownTable(cellTable(st), 0) + "\n## Paired comparison\n\n";
  if (st.subject.empty()) return md + "No controller under test among the controllers (compare: {subject}).\n";
  return md + comparisonExplanation(st.subject) + "\n\n" + kFewPairsNote + "\n\n" +
         markdownTable(comparisonTable(st), 1);
}

run_files::Json statisticsJson(const ExperimentStatistics& st) {
  run_files::Json per_scene = run_files::Json::object();
  for (std::size_t s = 0; s < st.scenes.size(); ++s) {
    run_files::Json scene = run_files::Json::object();
    for (std::size_t c = 0; c < st.controllers.size(); ++c) scene[st.controllers[c]] = cellJson(st.cells[c][s]);
    per_scene[st.scenes[s]] = scene;
  }
  run_files::Json paired = run_files::Json::object();
  for (const BaselineComparison& b : st.comparisons) {
    run_files::Json scenes = run_files::Json::object();
    for (std::size_t s = 0; s < st.scenes.size(); ++s) scenes[st.scenes[s]] = comparisonJson(b.per_scene[s]);
    paired[b.controller] = {{"scenes", scenes}, {"pooled", comparisonJson(b.pooled)}};
  }
  return {{"per_scene", per_scene},
          {"subject", st.subject},
          {"paired", paired},
          {"note",
           "ratios are subject / other; p: two-sided Wilcoxon signed-rank on paired ATE differences (subject - "
           "other), zero differences dropped, exact for n <= 25 without ties, else normal approximation with tie "
           "and continuity correction"}};
}

}  // namespace uampc::app
