// Hand-made run directories with the files the evaluator writes, for testing the results table and
// the report without running anything. Their figures are invented: never results.
#pragma once

#include <string>
#include <vector>

#include "experiment/experiment_file.hpp"
#include "experiment/run_results.hpp"

namespace uampc::test {

// Scenes alpha and beta, controllers ua_mpc, constant_3.6 and zero, seeds 1 and 2, under dir.
// ATE (m) and CMPLT per run are listed in fake_runs.cpp; zero/beta/seed2 failed (no done marker)
// and zero/alpha has no CMPLT (null, as a run shorter than one window). Distance travelled: 50 m
// in alpha, 200 m in beta.
struct FakeExperiment {
  std::string directory;  // the experiment's output directory
  app::Experiment experiment;
  std::vector<app::RunResult> results;
};
FakeExperiment makeFakeExperiment(const std::string& directory);

// Writes text to path, creating folders.
void writeText(const std::string& path, const std::string& text);

}  // namespace uampc::test
