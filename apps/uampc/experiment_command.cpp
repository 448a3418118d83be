#include "experiment_command.hpp"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "experiment_file.hpp"
#include "experiment_runner.hpp"
#include "report_page.hpp"
#include "results_table.hpp"
#include "run_results.hpp"
#include "uampc/runtime/scene.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

// Every scene with every controller's overrides, validated as `uampc launch` will, before the
// first run starts: a typo in a controller's override should cost seconds, not an hour of runs.
bool validateScenes(const Experiment& experiment, const std::vector<PlannedRun>& plan, int domain_base) {
  ComponentCatalog catalog;
  bool ok = true;
  for (const PlannedRun& run : plan) {
    if (run.seed != experiment.seeds.front()) continue;  // seeds do not change what is valid
    std::vector<Override> overrides;
    for (std::size_t i = 2; i + 1 < run.args.size(); i += 2) overrides.push_back(parseOverride(run.args[i + 1]));
    overrides.push_back(parseOverride("domain_id=" + std::to_string(domain_base)));
    try {
      loadScene(run.args[1], overrides, catalog);
    } catch (const SceneError& e) {
      ok = false;
      std::cerr << "uampc experiment: scene '" << experiment.scenes[run.scene].name << "' with controller '"
                << experiment.controllers[run.controller].name << "' (" << experiment.scenes[run.scene].location << ", "
                << experiment.controllers[run.controller].location << "):\n";
      for (const auto& m : e.messages()) std::cerr << "  " << m << "\n";
    }
  }
  return ok;
}

}  // namespace

std::string experimentOptionsError(const ExperimentOptions& options) {
  for (const std::string& text : options.overrides) {
    try {
      const Override parsed = parseOverride(text);
      if (parsed.path.size() == 1 && (parsed.path[0] == "seed" || parsed.path[0] == "domain_id")) {
        return "--set " + text + ": " + parsed.path[0] + " is set by the experiment";
      }
    } catch (const SceneError& e) {
      return e.what();
    }
  }
  if (options.domain_base + options.jobs - 1 > kHighestDomainId) {
    return "--domain-base " + std::to_string(options.domain_base) + " with --jobs " + std::to_string(options.jobs) +
           " needs DDS domains above " + std::to_string(kHighestDomainId);
  }
  return "";
}

int experimentCommand(const ExperimentOptions& options) {
  std::map<std::string, std::string> variables;
  if (!options.data_directory.empty()) {
    variables["data_dir"] = fs::absolute(options.data_directory).lexically_normal().string();
  }
  Experiment experiment;
  try {
    experiment = loadExperiment(options.experiment_file, variables);
  } catch (const ExperimentError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    return 2;
  }
  const std::vector<PlannedRun> plan = planRuns(experiment, options.overrides);
  if (!validateScenes(experiment, plan, options.domain_base)) return 2;
  if (options.dry_run) {
    for (const PlannedRun& run : plan) {
      std::cout << run.directory << ":";
      for (const auto& a : run.args) std::cout << " " << a;
      std::cout << "\n";
    }
    std::cerr << "uampc experiment: " << plan.size() << " runs valid; nothing run (--dry-run)\n";
    return 0;
  }

  fs::create_directories(options.output_directory);
  catchStopSignals();
  std::cerr << "uampc experiment " << experiment.name << ": " << plan.size() << " runs (" << experiment.scenes.size()
            << " scenes x " << experiment.controllers.size() << " controllers x " << experiment.seeds.size()
            << " seeds), " << options.jobs << " at a time on DDS domains " << options.domain_base << ".."
            << options.domain_base + options.jobs - 1 << ", into " << options.output_directory << "\n";

  RunnerOptions runner;
  runner.output_directory = options.output_directory;
  runner.jobs = options.jobs;
  runner.domain_base = options.domain_base;
  runner.interrupted = &stopFlag();
  const std::vector<RunResult> results = runAll(experiment, plan, runner);

  const ResultsTable table = summarize(experiment, results);
  const fs::path out(options.output_directory);
  writeResultsJson((out / "results.json").string(), experiment, results);
  const std::string markdown = renderMarkdown(experiment, table, results);
  std::ofstream((out / "results.md").string()) << markdown;
  const ReportSummary report = writeReport(experiment, results, table, options.output_directory);

  std::size_t failed = 0, not_run = 0;
  for (const RunResult& r : results) {
    failed += r.status == RunStatus::kFailed;
    not_run += r.status == RunStatus::kNotRun;
  }
  // The paper's table, as in results.md, for the terminal.
  std::cout << markdown.substr(0, markdown.find("\n## Runs")) << "\n";
  std::cerr << "uampc experiment: results in " << (out / "results.md").string() << " and "
            << (out / "results.json").string() << "; report " << (out / "report" / "index.html").string() << " ("
            << report.figures << " figures)\n";
  if (failed) std::cerr << "uampc experiment: " << failed << " run(s) failed; run again to retry them\n";
  if (stopRequested()) return 130;
  return failed ? 1 : 0;
}

}  // namespace uampc::app
