// The paper's table (docs/dev/architecture.md section 1): one row per controller, "<scene> ATE m" and
// "<scene> CMPLT" per scene as means over seeds, and a row-wise summary: the ATE summed over
// scenes, its ratio to the baseline's (the paper: UA-MPC more than 60% below constant speed) and
// CMPLT per scene relative to the baseline (the paper: less than 2% below).
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"
#include "experiment/run_results.hpp"

namespace uampc::app {

struct MeanOverSeeds {
  double mean = kMissing;  // NaN when no finished run has the figure
  int runs = 0;            // finished runs with a finite figure
};

// s of simulated time within which a loss of track counts as a start-up loss: the LO's thin first map
// decides it, not the controller (docs/decisions/start-hold.md).
inline constexpr double kStartUpLossWindowS = 10.0;

struct ResultsTable {
  std::vector<std::string> scenes;
  std::vector<std::string> controllers;
  int seeds = 0;                                  // planned per cell
  std::vector<std::vector<MeanOverSeeds>> ate;    // [controller][scene], m
  std::vector<std::vector<MeanOverSeeds>> cmplt;  // [controller][scene], voxels per window
  std::vector<double> ate_sum;                    // [controller]; NaN if a scene has no ATE
  std::vector<double> ate_sum_ratio;              // [controller] ate_sum / baseline's
  std::vector<std::vector<double>> cmplt_ratio;   // [controller][scene] cmplt / baseline's
  // [controller][scene]: finished runs, and of those the ones that lost track (ran away: their
  // estimated speed strayed more than 1 m/s from the truth's). A mean over seeds hides a lost run;
  // this does not.
  std::vector<std::vector<int>> finished_runs, lost_runs;
  std::vector<std::vector<int>> start_up_lost_runs;  // of lost_runs, lost within kStartUpLossWindowS
  std::vector<std::vector<int>> recovered_runs;      // not lost, with velocity resets of the LO
  std::string subject;
  std::string baseline;
  int subject_index = -1;  // -1: not among the controllers
  int baseline_index = -1;
};

ResultsTable summarize(const Experiment& experiment, const std::vector<RunResult>& results);

// results.md: the table above, the headline sentence, and every run with status and speed.
std::string renderMarkdown(const Experiment& experiment, const ResultsTable& table,
                           const std::vector<RunResult>& results);

// Cell texts shared by Markdown and HTML: ATE with 2 decimals (as the paper), CMPLT as an
// integer, ratios with 2 decimals; "n/a" for missing; "(k/n)" when fewer seeds finished.
std::string formatAte(const MeanOverSeeds& cell, int seeds);
std::string formatCmplt(const MeanOverSeeds& cell, int seeds);
std::string formatRatio(double ratio);
// "UA-MPC (ua_mpc) vs constant_3.6: ATE sum -61% ..." or empty when the comparison is impossible.
std::string headline(const ResultsTable& table);

}  // namespace uampc::app
