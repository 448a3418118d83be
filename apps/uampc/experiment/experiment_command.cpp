#include "experiment/experiment_command.hpp"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "cli/command_set.hpp"
#include "experiment/backends/backend_outcome.hpp"
#include "experiment/backends/experiment_runner.hpp"
#include "experiment/backends/slurm_backend.hpp"
#include "experiment/experiment_collect.hpp"
#include "experiment/experiment_file.hpp"
#include "experiment/experiment_snapshot.hpp"
#include "experiment/experiment_task.hpp"
#include "experiment/output_lock.hpp"
#include "experiment/plan_directories.hpp"
#include "experiment/run_completion.hpp"
#include "experiment/run_results.hpp"
#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/scene.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace fs = std::filesystem;

namespace uampc::app {

namespace {

void sayWhatIsWrong(const Experiment& experiment, const PlannedRun& run, const std::vector<std::string>& messages) {
  std::cerr << "uampc experiment: scene '" << experiment.scenes[run.scene].name << "' with controller '"
            << experiment.controllers[run.controller].name << "' (" << experiment.scenes[run.scene].location << ", "
            << experiment.controllers[run.controller].location << "):\n";
  for (const auto& m : messages) std::cerr << "  " << m << "\n";
}

// Every scene with every controller's overrides, validated as `uampc launch` will, before the
// first run starts: a typo in a controller's override should cost seconds, not an hour of runs.
// Each run gets its scene's end (what counts as done, run_completion.hpp); a scene without one
// is refused. `scenes_with_profile` gets the scenes that name a dds_profile of their own.
bool validateScenes(const Experiment& experiment, std::vector<PlannedRun>& plan, int domain_base,
                    std::set<std::size_t>& scenes_with_profile) {
  ComponentCatalog catalog;
  bool ok = true;
  std::map<std::pair<std::size_t, std::size_t>, SceneEnd> ends;  // by scene and controller
  for (const PlannedRun& run : plan) {
    if (run.seed != experiment.seeds.front()) continue;  // seeds change neither what is valid nor the end
    std::vector<Override> overrides;
    for (std::size_t i = 2; i + 1 < run.args.size(); i += 2) overrides.push_back(parseOverride(run.args[i + 1]));
    overrides.push_back(parseOverride("domain_id=" + std::to_string(domain_base)));
    try {
      const Scene scene = loadScene(run.args[1], overrides, catalog);
      if (!scene.dds_profile.empty()) scenes_with_profile.insert(run.scene);
      std::string problem;
      ends[{run.scene, run.controller}] = sceneEndOf(scene, &problem);
      if (!problem.empty()) {
        ok = false;
        sayWhatIsWrong(experiment, run, {scene.file + ": error: " + problem});
      }
    } catch (const SceneError& e) {
      ok = false;
      sayWhatIsWrong(experiment, run, e.messages());
    }
  }
  for (PlannedRun& run : plan) run.end = ends[{run.scene, run.controller}];
  return ok;
}

}  // namespace

std::string experimentOptionsError(const ExperimentOptions& options) {
  const bool collecting = !options.collect_directory.empty(), task = options.run_task >= 0;
  if (collecting && task) return "--collect and --run-task: give one of them";
  if ((collecting || task) && !options.experiment_file.empty()) {
    return std::string(collecting ? "--collect" : "--run-task") + " reads the experiment from " +
           kExperimentSnapshotFile + " in its directory: give no EXPERIMENT.yaml";
  }
  if (!collecting && !task && options.experiment_file.empty()) return "EXPERIMENT.yaml is required";
  if (!collecting && options.output_directory.empty()) return "--out is required";
  if (options.plan_only && (options.dry_run || options.backend == "slurm")) {
    return "--plan-only runs nothing and submits nothing: not with --dry-run or --backend slurm";
  }
  if (options.backend != "slurm" && (!options.partition.empty() || !options.time_limit.empty() ||
                                     !options.sbatch_options.empty() || options.no_wait)) {
    return "--partition, --time, --sbatch-option and --no-wait need --backend slurm";
  }
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
  if (options.backend == "local" && options.domain_base + options.jobs - 1 > kHighestDomainId) {
    return "--domain-base " + std::to_string(options.domain_base) + " with --jobs " + std::to_string(options.jobs) +
           " needs DDS domains above " + std::to_string(kHighestDomainId);
  }
  return "";
}

namespace {

// For schedulers (Slurm, a Kubernetes Indexed Job): every run of a scene without a dds_profile of
// its own gets the host-only one (slurm_backend.hpp), whose file is written beside the plan.
ExperimentSnapshot withHostOnlyDds(ExperimentSnapshot snapshot, const std::set<std::size_t>& scenes_with_profile,
                                   const std::string& out) {
  for (PlannedRun& run : snapshot.plan) {
    if (scenes_with_profile.count(run.scene)) continue;
    run.args.push_back("--set");
    run.args.push_back(hostOnlyDdsOverride(out));
  }
  for (std::size_t scene : scenes_with_profile) {
    std::cerr << "uampc experiment: warning: scene '" << snapshot.experiment.scenes[scene].name
              << "' has a dds_profile of its own: its runs keep it, so it must keep their DDS traffic on their host "
                 "(runs on other nodes may share their domain)\n";
  }
  writeHostOnlyDdsProfile(out);
  return snapshot;
}

BackendOutcome submitToSlurm(const ExperimentSnapshot& snapshot, const std::string& out,
                             const ExperimentOptions& options) {
  SlurmOptions slurm;
  slurm.partition = options.partition;
  slurm.time_limit = options.time_limit;
  slurm.sbatch_options = options.sbatch_options;
  slurm.wait = !options.no_wait;
  slurm.domain_base = options.domain_base;
  return runOnSlurm(snapshot, out, slurm);
}

// --plan-only: the plan for a scheduler uampc does not submit to itself.
int writePlanOnly(const ExperimentSnapshot& snapshot, const std::string& out) {
  writeExperimentSnapshot(out, snapshot);
  std::cerr << "uampc experiment: " << snapshot.plan.size() << " runs planned in " << out << "/"
            << kExperimentSnapshotFile << "; run K with `uampc experiment --run-task K --out " << out << "` (K = 0.."
            << snapshot.plan.size() - 1 << ", e.g. a Kubernetes Indexed Job with completions: " << snapshot.plan.size()
            << ", docker/k8s/), then `uampc experiment --collect " << out << "`\n";
  return 0;
}

BackendOutcome runLocally(const ExperimentSnapshot& snapshot, const ExperimentOptions& options) {
  const Experiment& experiment = snapshot.experiment;
  writeExperimentSnapshot(options.output_directory, snapshot);
  catchStopSignals();
  std::cerr << "uampc experiment " << experiment.name << ": " << snapshot.plan.size() << " runs ("
            << experiment.scenes.size() << " scenes x " << experiment.controllers.size() << " controllers x "
            << experiment.seeds.size() << " seeds), " << options.jobs << " at a time on DDS domains "
            << options.domain_base << ".." << options.domain_base + options.jobs - 1 << ", into "
            << options.output_directory << "\n";
  RunnerOptions runner;
  runner.output_directory = options.output_directory;
  runner.jobs = options.jobs;
  runner.domain_base = options.domain_base;
  runner.interrupted = &stopFlag();
  RunnerOutcome ran = runAll(experiment, snapshot.plan, runner);
  if (!ran.error.empty()) {
    std::cerr << "uampc experiment: stopped: " << ran.error << "; no results written (run the same command again "
              << "to resume once the directory can be written)\n";
    return BackendOutcome{std::nullopt, 1, false};
  }
  BackendOutcome outcome{std::move(ran.results)};
  outcome.interrupted = stopRequested();
  return outcome;
}

// The one place results.md, results.json and the report are written, whichever backend ran.
int writeOutcome(const Experiment& experiment, const BackendOutcome& outcome, const std::string& out) {
  if (!outcome.results) return outcome.exit_code;
  const int code = writeExperimentOutputs(experiment, *outcome.results, out);
  return outcome.interrupted ? 130 : code;
}

// The output directory, made if missing; "" or why it cannot be (the reason as the system gives it:
// a read-only file system, a name too long, a file in the way).
std::string createOutputDirectory(const std::string& directory) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (!error && !isDirectory(directory)) error = std::make_error_code(std::errc::not_a_directory);
  return error ? "cannot create the output directory " + directory + ": " + error.message() : "";
}

int runExperiment(const ExperimentOptions& options) {
  if (!options.collect_directory.empty()) return collectCommand(options.collect_directory);
  if (options.run_task >= 0)
    return experimentTaskCommand(options.output_directory, options.run_task, options.domain_base);
  std::map<std::string, std::string> variables;
  if (!options.data_directory.empty()) {
    variables["data_dir"] = fs::absolute(options.data_directory).lexically_normal().string();
  }
  ExperimentSnapshot snapshot;
  try {
    snapshot.experiment = loadExperiment(options.experiment_file, variables);
  } catch (const ExperimentError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    return 2;
  }
  snapshot.plan = planRuns(snapshot.experiment, options.overrides);
  std::set<std::size_t> scenes_with_profile;
  if (!validateScenes(snapshot.experiment, snapshot.plan, options.domain_base, scenes_with_profile)) return 2;
  if (options.dry_run) {
    for (const PlannedRun& run : snapshot.plan) {
      std::cout << run.directory << ":";
      for (const auto& a : run.args) std::cout << " " << a;
      std::cout << "\n";
    }
    std::cerr << "uampc experiment: " << snapshot.plan.size() << " runs valid; nothing run (--dry-run)\n";
    return 0;
  }
  if (const std::string problem = createOutputDirectory(options.output_directory); !problem.empty()) {
    std::cerr << "uampc experiment: " << problem << "; nothing was run\n";
    return 1;
  }
  // Held until the command ends: the runs, the results and the report are this command's.
  const std::optional<FileLock> lock =
      lockOutputDirectory(options.output_directory, "uampc experiment " + options.experiment_file);
  if (!lock) return 2;
  if (const std::string problem = planDirectoriesProblem(options.output_directory, snapshot.plan); !problem.empty()) {
    std::cerr << "uampc experiment: " << problem << "; nothing was run\n";
    return 2;
  }
  if (options.backend == "local" && !options.plan_only) {
    return writeOutcome(snapshot.experiment, runLocally(snapshot, options), options.output_directory);
  }
  // Scheduled elsewhere: absolute paths, for tasks that start in another directory.
  const std::string out = fs::absolute(options.output_directory).lexically_normal().string();
  snapshot = withHostOnlyDds(std::move(snapshot), scenes_with_profile, out);
  if (options.plan_only) return writePlanOnly(snapshot, out);
  return writeOutcome(snapshot.experiment, submitToSlurm(snapshot, out, options), out);
}

}  // namespace

int experimentCommand(const ExperimentOptions& options) {
  // A file the experiment cannot write (its plan, results, report, a Slurm script; run_files'
  // writers name the file and the reason and leave no half of it) ends it with that message and
  // exit code 1, as `uampc launch --out` does; the runs' own files are the runner's (halt()).
  try {
    return runExperiment(options);
  } catch (const std::runtime_error& e) {
    std::cerr << "uampc experiment: " << e.what() << "\n";
    return 1;
  }
}

void addExperimentCommand(CommandSet& commands) {
  auto options = std::make_shared<ExperimentOptions>();
  ExperimentOptions& o = *options;
  CLI::App* sub = commands.add(
      "experiment",
      "uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--domain-base N]\n"
      "[--set NAME=VALUE ...] [--dry-run | --plan-only] [--backend local|slurm [--partition P] [--time T] "
      "[--no-wait]]\n"
      "uampc experiment --collect DIR\n"
      "uampc experiment --run-task K --out DIR [--domain-base N]",
      "Run every scene x controller x seed of an experiment (at most N at once, default: one per\n"
      "CPU, each on DDS domain domain-base (100) + its slot), then write DIR/results.json,\n"
      "DIR/results.md (the paper's table) and DIR/report/index.html. A run is done when it exited 0\n"
      "and its sim time reached its scene's end; done runs are kept: running it again only runs the\n"
      "others. One command at a time on DIR (it holds DIR/experiment.lock; a second is refused, exit 2).\n"
      "${data_dir} in the experiment's overrides is --data-dir. --set applies to every run.\n"
      "--dry-run only validates and lists the runs.\n"
      "--backend slurm submits the unfinished runs as one Slurm job array instead (DIR on a filesystem\n"
      "the nodes share), watches it and collects; --collect DIR builds the results from DIR's run\n"
      "directories wherever they ran; --run-task K runs planned run K of DIR (what an array task does;\n"
      "it takes no lock of DIR, only its run's, and leaves a run another attempt holds alone).\n"
      "Exit codes: 0 every run done, 1 a run failed or was cut short, 2 invalid, or DIR in use, 130 Ctrl-C.");
  sub->add_option("EXPERIMENT.yaml", o.experiment_file, "The experiment file.")->type_name("");
  sub->add_option("--out", o.output_directory, "Write the runs, results and report into DIR.")->type_name("DIR");
  sub->add_option("--jobs", o.jobs,
                  "Run at most N (1 to " + std::to_string(kMostJobs) + ") at once (default: one per CPU).")
      ->check(CLI::Range(1, kMostJobs).description(""))
      ->type_name("N");
  sub->add_option("--data-dir", o.data_directory, "What ${data_dir} in the experiment's overrides stands for.")
      ->type_name("DIR");
  sub->add_option("--domain-base", o.domain_base,
                  "The first run's DDS domain; slot k runs on N + k (default " + std::to_string(kDefaultDomainBase) +
                      ", at most " + std::to_string(kHighestDomainId) +
                      " with the slots). On Slurm, each\ntask takes the first domain from N that no "
                      "other task on its node holds.")
      ->check(CLI::Range(0, kHighestDomainId).description(""))
      ->type_name("N");
  sub->add_option("--set", o.overrides,
                  "Override a value of every run's scene (NAME=VALUE as for launch;\n"
                  "not seed or domain_id, which the experiment sets). Repeatable.")
      ->allow_extra_args(false)
      ->type_name("NAME=VALUE");
  sub->add_flag("--dry-run", o.dry_run, "Only validate the experiment and its scenes and list the runs.");
  sub->add_option("--backend", o.backend,
                  "local (default): runs as child processes here; slurm: one Slurm job array, one task per run.")
      ->check(CLI::IsMember({"local", "slurm"}).description(""))
      ->type_name("local|slurm");
  sub->add_option("--partition", o.partition, "Slurm: the partition to submit to (default: the cluster's).")
      ->type_name("P");
  sub->add_option("--time", o.time_limit, "Slurm: the time limit of each run's task, as sbatch --time takes it.")
      ->type_name("T");
  sub->add_option("--sbatch-option", o.sbatch_options,
                  "Slurm: one more sbatch option for the job array, e.g. --sbatch-option=--mem=2G. Repeatable.")
      ->allow_extra_args(false)
      ->type_name("OPTION");
  sub->add_flag("--plan-only", o.plan_only,
                "Write DIR/experiment.json and run nothing: for a scheduler that runs --run-task K itself\n"
                "(docker/k8s/experiment-indexed-job.yaml).");
  sub->add_flag("--no-wait", o.no_wait, "Slurm: submit and return; --collect DIR builds the results later.");
  sub->add_option("--collect", o.collect_directory,
                  "Build DIR/results.json, results.md and the report from DIR's finished run directories.")
      ->type_name("DIR");
  sub->add_option("--run-task", o.run_task,
                  "Run planned run K of --out DIR (what a Slurm array task runs); exit 4 when another attempt\n"
                  "holds the run.")
      ->check(CLI::Range(0L, 1000000L).description(""))
      ->type_name("K");
  commands.onRun(sub, [&commands, sub, options] {
    const std::string error = experimentOptionsError(*options);
    if (!error.empty()) return commands.usageError(sub, error);
    return experimentCommand(*options);
  });
}

}  // namespace uampc::app
