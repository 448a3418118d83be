#include "experiment/experiment_collect.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "experiment/output_lock.hpp"
#include "experiment/run_completion.hpp"
#include "report/report_page.hpp"
#include "report/results_table.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/text_file.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

// Each run left out of the table, by name, with why: a count alone does not say which to look at.
void sayRunsNotDone(const std::vector<RunResult>& results) {
  for (const RunResult& r : results) {
    if (r.finished()) continue;
    std::cerr << "uampc experiment: " << r.directory << " " << statusName(r.status)
              << (r.failure.empty() ? "" : ": " + r.failure) << "\n";
  }
}

}  // namespace

std::vector<RunResult> collectRuns(const ExperimentSnapshot& snapshot, const std::string& output_directory) {
  std::vector<RunResult> results;
  for (const PlannedRun& run : snapshot.plan) {
    RunResult r = plannedResult(snapshot.experiment, run);
    const std::string dir = (fs::path(output_directory) / run.directory).string();
    const RunCompletion completion = runCompletion(dir, run.end);
    if (completion.state == RunState::kDone) {
      r.status = RunStatus::kOk;
      r.exit_code = 0;
      readRunOutputs(dir, r);
    } else {
      r.status = completion.state == RunState::kFailed ? RunStatus::kFailed : RunStatus::kNotRun;
      r.failure = completion.reason;
      if (auto metrics = readRunMetrics(dir)) r.metrics = *metrics;  // how far it got, for results.json
    }
    results.push_back(std::move(r));
  }
  return results;
}

int writeExperimentOutputs(const Experiment& experiment, const std::vector<RunResult>& results,
                           const std::string& output_directory) {
  const ResultsTable table = summarize(experiment, results);
  const fs::path out(output_directory);
  writeResultsJson((out / "results.json").string(), experiment, results);
  const std::string markdown = renderMarkdown(experiment, table, results);
  run_files::writeTextFile((out / "results.md").string(), markdown);
  const ReportSummary report = writeReport(experiment, results, table, output_directory);

  std::size_t failed = 0, not_run = 0;
  for (const RunResult& r : results) {
    failed += r.status == RunStatus::kFailed;
    not_run += r.status == RunStatus::kNotRun;
  }
  sayRunsNotDone(results);
  // The paper's table, as in results.md, for the terminal.
  std::cout << markdown.substr(0, markdown.find("\n## Runs")) << "\n";
  std::cerr << "uampc experiment: results in " << (out / "results.md").string() << " and "
            << (out / "results.json").string() << "; report " << (out / "report" / "index.html").string() << " ("
            << report.figures << " figures)\n";
  if (failed) std::cerr << "uampc experiment: " << failed << " run(s) failed; run again to retry them\n";
  if (not_run) std::cerr << "uampc experiment: " << not_run << " run(s) did not finish\n";
  return failed || not_run ? 1 : 0;
}

int collectCommand(const std::string& output_directory) {
  ExperimentSnapshot snapshot;
  try {
    snapshot = readExperimentSnapshot(output_directory);
  } catch (const ExperimentError& e) {
    for (const auto& m : e.messages()) std::cerr << "uampc experiment --collect: " << m << "\n";
    return 2;
  }
  const std::optional<FileLock> lock = lockOutputDirectory(output_directory, "uampc experiment --collect");
  if (!lock) return 2;
  const std::vector<RunResult> results = collectRuns(snapshot, output_directory);
  std::size_t finished = 0;
  for (const RunResult& r : results) finished += r.finished();
  std::cerr << "uampc experiment --collect: " << finished << " of " << results.size() << " runs of "
            << snapshot.experiment.name << " finished\n";
  return writeExperimentOutputs(snapshot.experiment, results, output_directory);
}

}  // namespace uampc::app
