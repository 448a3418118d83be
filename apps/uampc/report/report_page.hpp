// The experiment's HTML report: OUT/report/index.html with the paper's table and figures as SVG
// files beside it (per scene: a box plot of every run's ATE per controller, ATE and motor speed
// over time per controller, top view of the trajectories over the scanned voxels, U(theta) over
// time of the controller under test, ATE against CMPLT).
// Each figure is an <img>; a small inline script writes "figures loaded: N of M" into
// #figure-check once the page has loaded, so a headless browser can tell that every figure renders.
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"
#include "report/results_table.hpp"
#include "experiment/run_results.hpp"

namespace uampc::app {

struct ReportSummary {
  int figures = 0;                 // <img> elements in index.html
  std::vector<std::string> notes;  // figures left out, and why
};

ReportSummary writeReport(const Experiment& experiment, const std::vector<RunResult>& results,
                          const ResultsTable& table, const std::string& output_directory);

}  // namespace uampc::app
