// The uampc command line.
//
//   uampc launch SCENE.yaml [--set NAME=VALUE ...] [--out DIR]
//   uampc components [--json]
//   uampc validate SCENE.yaml [--set NAME=VALUE ...]
//   uampc graph SCENE.yaml [--set NAME=VALUE ...] [--format mermaid|dot]
//   uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--set NAME=VALUE ...]
//   uampc run-process SCENE.yaml --process NAME ...;  uampc clock SCENE.yaml ...
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "components_command.hpp"
#include "experiment_command.hpp"
#include "graph_command.hpp"
#include "uampc/runtime/launcher.hpp"

namespace {

const char* const kUsage = R"(usage:
  uampc launch SCENE.yaml [--set NAME=VALUE ...] [--out DIR]
      Validate and run a scene. NAME is component.parameter, clock.key or a top-level key
      (seed, domain_id, ...). --out DIR collects the run's outputs. Ctrl-C stops everything.
  uampc validate SCENE.yaml [--set NAME=VALUE ...]
      Only validate the scene; print every problem with file:line:column.
  uampc graph SCENE.yaml [--set NAME=VALUE ...] [--format mermaid|dot]
      Print the scene's resolved graph (components, and the topics between them with their types)
      as a Mermaid flowchart (default) or Graphviz DOT.
  uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--domain-base N]
                   [--set NAME=VALUE ...] [--dry-run]
      Run every scene x controller x seed of an experiment (at most N at once, default: one per
      CPU, each on DDS domain domain-base (100) + its slot), then write DIR/results.json,
      DIR/results.md (the paper's table) and DIR/report/index.html. Finished runs are kept:
      running it again only runs what is missing or failed. ${data_dir} in the experiment's
      overrides is --data-dir. --set applies to every run. --dry-run only validates and lists the runs.
  uampc components [--json]
      List installed component types with their ports and parameters.
  uampc run-process SCENE.yaml --process NAME [--set NAME=VALUE ...] [--out DIR]
      Run one process group of a scene (launch does this for every group; use it to spread a
      scene over containers or hosts).
  uampc clock SCENE.yaml [--set NAME=VALUE ...]
      Run only the lockstep clock of a scene whose process groups were started with run-process.

Component libraries are searched in $UAMPC_COMPONENT_PATH (colon-separated), then next to this binary
in ../lib/uampc/components. Log level: UAMPC_LOG_LEVEL=debug|info|warn|error.
Exit codes: 0 success, 1 run failed, 2 bad scene or command line, 130 Ctrl-C.
)";

int usageError(const std::string& message) {
  std::cerr << "uampc: " << message << "\n\n" << kUsage;
  return 2;
}

// Parses SCENE [--set X=Y]... [--out DIR] [--process P] into options.
bool parseLaunchArguments(const std::vector<std::string>& args, uampc::LaunchOptions& options,
                          std::string* process, std::string& error) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const char* flag) -> const std::string* {
      if (i + 1 >= args.size()) {
        error = std::string(flag) + " needs a value";
        return nullptr;
      }
      return &args[++i];
    };
    if (a == "--set") {
      const std::string* v = value("--set");
      if (!v) return false;
      try {
        options.overrides.push_back(uampc::parseOverride(*v));
      } catch (const std::exception& e) {
        error = e.what();
        return false;
      }
    } else if (a == "--out") {
      const std::string* v = value("--out");
      if (!v) return false;
      options.output_directory = *v;
    } else if (a == "--process" && process) {
      const std::string* v = value("--process");
      if (!v) return false;
      *process = *v;
    } else if (!a.empty() && a[0] == '-') {
      error = "unknown option " + a;
      return false;
    } else if (options.scene_path.empty()) {
      options.scene_path = a;
    } else {
      error = "more than one scene given: " + options.scene_path + " and " + a;
      return false;
    }
  }
  if (options.scene_path.empty()) {
    error = "no scene file given";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::cout << kUsage;
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  std::string error;
  uampc::LaunchOptions options;
  if (command == "launch") {
    if (!parseLaunchArguments(args, options, nullptr, error)) return usageError(error);
    return uampc::launch(options);
  }
  if (command == "validate") {
    if (!parseLaunchArguments(args, options, nullptr, error)) return usageError(error);
    return uampc::app::validateCommand(options);
  }
  if (command == "clock") {
    if (!parseLaunchArguments(args, options, nullptr, error)) return usageError(error);
    return uampc::runClockCommand(options);
  }
  if (command == "run-process") {
    std::string process;
    if (!parseLaunchArguments(args, options, &process, error) || process.empty()) {
      return usageError(error.empty() ? "run-process needs --process" : error);
    }
    return uampc::runProcessCommand(options, process);
  }
  if (command == "graph") return uampc::app::graphCommand(args);
  if (command == "experiment") return uampc::app::experimentCommand(args);
  if (command == "components") {
    if (args.size() > 1 || (args.size() == 1 && args[0] != "--json")) return usageError("components takes only --json");
    return uampc::app::componentsCommand(args.size() == 1);
  }
  return usageError("unknown command '" + command + "'");
}
