// The commands that take a scene (launch, validate, graph, run-process, clock) and their options:
// the scene file, --set overrides, --out, and what each adds. What they do is in launcher.hpp,
// graph_command.hpp and components_command.hpp.
#include "commands/scene_commands.hpp"

#include <memory>

#include "commands/components_command.hpp"
#include "commands/graph_command.hpp"
#include "commands/version.hpp"
#include "uampc/runtime/launcher.hpp"
#include "view/view_command.hpp"

namespace uampc::app {

namespace {

const char* const kSetHelp =
    "Override a value of the scene: component.parameter, clock.key, rig.key or a top-level key\n"
    "(seed, domain_id, ...). Repeatable; applied in the order given.";

struct SceneCommandOptions {
  LaunchOptions scene;
  std::vector<std::string> overrides;    // --set, as given, parsed into scene.overrides
  std::string process;                   // run-process
  bool own_clock = false;                // run-process
  std::string graph_format = "mermaid";  // graph
};
using Options = std::shared_ptr<SceneCommandOptions>;

void addScene(CLI::App* sub, SceneCommandOptions& o) {
  sub->add_option("SCENE.yaml", o.scene.scene_path, "The scene file.")->required()->type_name("");
}

void addOverrides(CLI::App* sub, SceneCommandOptions& o) {
  sub->add_option("--set", o.overrides, kSetHelp)->allow_extra_args(false)->type_name("NAME=VALUE");
}

void addOutput(CLI::App* sub, SceneCommandOptions& o) {
  sub->add_option("--out", o.scene.output_directory, "Collect the run's outputs in DIR.")->type_name("DIR");
}

// The command, after its --set values are parsed as the scene loader reads them.
std::function<int()> withOverrides(CommandSet& commands, CLI::App* sub, const Options& o,
                                   std::function<int()> command) {
  return [&commands, sub, o, command] {
    try {
      for (const std::string& text : o->overrides) o->scene.overrides.push_back(parseOverride(text));
    } catch (const SceneError& e) {
      return commands.usageError(sub, e.what());
    }
    return command();
  };
}

void addLaunch(CommandSet& commands) {
  auto o = std::make_shared<SceneCommandOptions>();
  CLI::App* sub = commands.add(
      "launch",
      "uampc launch SCENE.yaml [--set NAME=VALUE ...] [--out DIR [--overwrite]]\n"
      "[--view [--view-port P] [--view-address A] [--view-max-...]]",
      "Validate and run a scene. NAME is component.parameter, clock.key or a top-level key\n"
      "(seed, domain_id, ...). --out DIR collects the run's outputs, with DIR/scene.yaml (the\n"
      "resolved scene: launch it to run the same again) and DIR/run_info.json (scene, overrides,\n"
      "seed, versions, every parameter; also in DIR/metrics.json as \"run\"); a DIR that holds a run\n"
      "already is refused unless --overwrite is given. Ctrl-C stops\n"
      "everything, while starting or running (exit code 130; SIGTERM 143, SIGHUP 129: a run cut\n"
      "short, which DIR/metrics.json marks \"reached_end\": false). --view serves the run live to Foxglove\n"
      "(docs/user/viewing.md).");
  addScene(sub, *o);
  addOverrides(sub, *o);
  addOutput(sub, *o);
  sub->add_flag("--overwrite", o->scene.overwrite,
                "Write into --out DIR even if it holds a run already (its run_info.json or metrics.json);\n"
                "files the new run does not write are left as they are.");
  addViewerOptions(sub, o->scene.viewer);
  commands.onRun(sub, withOverrides(commands, sub, o, [o] {
                   o->scene.uampc_version = uampcVersion();  // for the run's record
                   o->scene.fastdds_version = fastDdsVersion();
                   return launch(o->scene);
                 }));
}

void addValidate(CommandSet& commands) {
  auto o = std::make_shared<SceneCommandOptions>();
  CLI::App* sub = commands.add("validate", "uampc validate SCENE.yaml [--set NAME=VALUE ...]",
                               "Only validate the scene; print every problem with file:line:column.");
  addScene(sub, *o);
  addOverrides(sub, *o);
  commands.onRun(sub, withOverrides(commands, sub, o, [o] { return validateCommand(o->scene); }));
}

void addGraph(CommandSet& commands) {
  auto o = std::make_shared<SceneCommandOptions>();
  CLI::App* sub =
      commands.add("graph", "uampc graph SCENE.yaml [--set NAME=VALUE ...] [--format mermaid|dot]",
                   "Print the scene's resolved graph (components, and the topics between them with their types)\n"
                   "as a Mermaid flowchart (default) or Graphviz DOT.");
  addScene(sub, *o);
  addOverrides(sub, *o);
  sub->add_option("--format", o->graph_format, "mermaid (default) or dot.")
      ->check(CLI::IsMember({"mermaid", "dot"}).description(""))
      ->type_name("mermaid|dot");
  commands.onRun(sub, withOverrides(commands, sub, o, [o] {
                   const auto format = o->graph_format == "dot" ? GraphFormat::kDot : GraphFormat::kMermaid;
                   return graphCommand(o->scene, format);
                 }));
}

void addRunProcess(CommandSet& commands) {
  auto o = std::make_shared<SceneCommandOptions>();
  CLI::App* sub = commands.add(
      "run-process", "uampc run-process SCENE.yaml --process NAME [--own-clock] [--set NAME=VALUE ...] [--out DIR]",
      "Run one process group of a scene (launch does this for every group; use it to spread a\n"
      "scene over containers or hosts).");
  addScene(sub, *o);
  sub->add_option("--process", o->process, "The process group to run (a process: of the scene).")
      ->required()
      ->type_name("NAME");
  sub->add_flag("--own-clock", o->own_clock,
                "Step this process group itself, from the other groups' acknowledgements, instead of following "
                "`uampc clock`: what launch passes to its children when clock.in_process is true; it then "
                "follows their progress (without launch, run `uampc clock` and leave this out).");
  addOverrides(sub, *o);
  addOutput(sub, *o);
  commands.onRun(
      sub, withOverrides(commands, sub, o, [o] { return runProcessCommand(o->scene, o->process, o->own_clock); }));
}

void addClock(CommandSet& commands) {
  auto o = std::make_shared<SceneCommandOptions>();
  CLI::App* sub =
      commands.add("clock", "uampc clock SCENE.yaml [--set NAME=VALUE ...]",
                   "Run only the lockstep clock of a scene whose process groups were started with run-process.");
  addScene(sub, *o);
  addOverrides(sub, *o);
  commands.onRun(sub, withOverrides(commands, sub, o, [o] { return runClockCommand(o->scene); }));
}

}  // namespace

void addSceneCommands(CommandSet& commands) {
  addLaunch(commands);
  addValidate(commands);
  addGraph(commands);
  addRunProcess(commands);
  addClock(commands);
}

}  // namespace uampc::app
