#include "experiment_command.hpp"

#include <signal.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <thread>

#include "experiment_file.hpp"
#include "experiment_runner.hpp"
#include "report_page.hpp"
#include "results_table.hpp"
#include "run_results.hpp"
#include "uampc/runtime/scene.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

std::atomic<bool> g_interrupted{false};

void onInterrupt(int) { g_interrupted = true; }

struct ExperimentOptions {
  std::string experiment_file;
  std::string output_directory;
  std::string data_directory;
  int jobs = std::max(1u, std::thread::hardware_concurrency());
  int domain_base = 100;
  bool dry_run = false;
  bool help = false;
  std::vector<std::string> overrides;
};

const char* const kExperimentUsage =
    "usage: uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--domain-base N] "
    "[--set NAME=VALUE ...] [--dry-run]\n";

bool parse(const std::vector<std::string>& args, ExperimentOptions& o, std::string& error) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string* {
      if (i + 1 >= args.size()) {
        error = a + " needs a value";
        return nullptr;
      }
      return &args[++i];
    };
    auto integer = [&](int lo, int hi, int& target) {
      const std::string* v = value();
      if (!v) return false;
      try {
        std::size_t used = 0;
        target = std::stoi(*v, &used);
        if (used == v->size() && target >= lo && target <= hi) return true;
      } catch (const std::exception&) {
      }
      error = a + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not '" + *v + "'";
      return false;
    };
    if (a == "--out") {
      const std::string* v = value();
      if (!v) return false;
      o.output_directory = *v;
    } else if (a == "--data-dir") {
      const std::string* v = value();
      if (!v) return false;
      o.data_directory = fs::absolute(*v).lexically_normal().string();
    } else if (a == "--dry-run") {
      o.dry_run = true;
    } else if (a == "--help" || a == "-h") {
      o.help = true;
      return true;
    } else if (a == "--jobs") {
      if (!integer(1, 133, o.jobs)) return false;
    } else if (a == "--domain-base") {
      if (!integer(0, 232, o.domain_base)) return false;
    } else if (a == "--set") {
      const std::string* v = value();
      if (!v) return false;
      try {
        const Override parsed = parseOverride(*v);
        if (parsed.path.size() == 1 && (parsed.path[0] == "seed" || parsed.path[0] == "domain_id")) {
          error = "--set " + *v + ": " + parsed.path[0] + " is set by the experiment";
          return false;
        }
      } catch (const SceneError& e) {
        error = e.what();
        return false;
      }
      o.overrides.push_back(*v);
    } else if (!a.empty() && a[0] == '-') {
      error = "unknown option " + a;
      return false;
    } else if (o.experiment_file.empty()) {
      o.experiment_file = a;
    } else {
      error = "more than one experiment file given: " + o.experiment_file + " and " + a;
      return false;
    }
  }
  if (o.experiment_file.empty())
    error = "no experiment file given";
  else if (o.output_directory.empty())
    error = "experiment needs --out DIR";
  if (!error.empty()) return false;
  if (o.domain_base + o.jobs - 1 > 232) {
    error = "--domain-base " + std::to_string(o.domain_base) + " with --jobs " + std::to_string(o.jobs) +
            " needs DDS domains above 232";
    return false;
  }
  return true;
}

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

int experimentCommand(const std::vector<std::string>& args) {
  ExperimentOptions options;
  std::string error;
  if (!parse(args, options, error)) {
    std::cerr << "uampc: " << error << "\n" << kExperimentUsage;
    return 2;
  }
  if (options.help) {  // the whole description is in `uampc --help`
    std::cout << kExperimentUsage << "(see uampc --help for what it does)\n";
    return 0;
  }
  std::map<std::string, std::string> variables;
  if (!options.data_directory.empty()) variables["data_dir"] = options.data_directory;
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
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::cerr << "uampc experiment " << experiment.name << ": " << plan.size() << " runs (" << experiment.scenes.size()
            << " scenes x " << experiment.controllers.size() << " controllers x " << experiment.seeds.size()
            << " seeds), " << options.jobs << " at a time on DDS domains " << options.domain_base << ".."
            << options.domain_base + options.jobs - 1 << ", into " << options.output_directory << "\n";

  RunnerOptions runner;
  runner.output_directory = options.output_directory;
  runner.jobs = options.jobs;
  runner.domain_base = options.domain_base;
  runner.interrupted = &g_interrupted;
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
  if (g_interrupted) return 130;
  return failed ? 1 : 0;
}

}  // namespace uampc::app
