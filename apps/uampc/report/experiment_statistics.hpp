// The experiment's statistics beyond the paper's means: per scene and controller how many runs
// held and lost track and robust ATE figures, and the controller under test (the experiment's
// compare.subject, UA-MPC) paired run by run (same scene, same seed) with every other controller,
// per scene and pooled over the scenes, with the Wilcoxon signed-rank test (paired_statistics.hpp).
// results.md, results.json ("statistics") and the report all show these figures.
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"
#include "uampc/plots/paired_statistics.hpp"
#include "experiment/run_results.hpp"
#include "uampc/run_files/json_text.hpp"

namespace uampc::app {

// One controller on one scene, over its finished runs.
struct CellStatistics {
  int runs = 0;  // finished
  int held = 0;  // finished without losing track
  int lost = 0;  // finished, but lost track (RunMetrics::runaway_time_s)
  double median_ate_m = kMissing, mean_ate_m = kMissing;
  // Median over runs of 100 ATE / distance travelled (the ground truth's path length); NaN when
  // no run has both (older evaluators wrote no distance).
  double median_ate_percent = kMissing;
  double median_cmplt = kMissing;
};

struct BaselineComparison {
  std::string controller;                   // the other controller
  std::vector<PairedComparison> per_scene;  // [scene]
  PairedComparison pooled;                  // every pair of every scene
};

struct ExperimentStatistics {
  std::vector<std::string> scenes, controllers;
  std::vector<std::vector<CellStatistics>> cells;  // [controller][scene]
  std::string subject;                             // empty when it is not among the controllers
  std::vector<BaselineComparison> comparisons;     // every controller but the subject, in order
};

// value with that many decimals ("%.*f"); "n/a" when it is not finite. Every table of the report prints
// through it.
std::string fixed(double value, int decimals);

ExperimentStatistics computeStatistics(const Experiment& experiment, const std::vector<RunResult>& results);

// The two tables as cell texts, shared by results.md and the report page; emphasised rows are the
// pooled ones (all scenes).
struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> emphasised;  // per row
};
TextTable cellTable(const ExperimentStatistics& statistics);
TextTable comparisonTable(const ExperimentStatistics& statistics);  // no rows without a subject
// What the tables' columns mean, for the text above them.
std::string cellTableExplanation();
std::string comparisonExplanation(const std::string& subject);
extern const char* const kFewPairsNote;  // why the pooled line matters

// results.md's sections "Per scene and controller" and "Paired comparison".
std::string statisticsMarkdown(const ExperimentStatistics& statistics);
// results.json's "statistics".
run_files::Json statisticsJson(const ExperimentStatistics& statistics);

}  // namespace uampc::app
