// The uampc command line: one CLI11 app with a subcommand per command. This file only turns the
// command line into each command's options; what a command does is in launcher.hpp and
// *_command.hpp. Every command and option is described here, once: `uampc --help` and
// `uampc COMMAND --help` print these texts.
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bag/play_command.hpp"
#include "bag/record_command.hpp"
#include "commands/components_command.hpp"
#include "commands/graph_command.hpp"
#include "commands/version.hpp"
#include "experiment/experiment_command.hpp"
#include "security/security_command.hpp"
#include "topic/topic_command.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/launcher.hpp"
#include "view/view_command.hpp"

namespace {

constexpr int kCommandLineError = 2;  // also "bad scene": both mean nothing ran

const char* const kFooter =
    R"(Component libraries are searched in $UAMPC_COMPONENT_PATH (colon-separated), then next to this binary
in ../lib/uampc/components. Log level: UAMPC_LOG_LEVEL=debug|info|warn|error.
Exit codes: 0 success, 1 run failed, 2 bad scene or command line, 130 Ctrl-C.)";

const char* const kSetHelp =
    "Override a value of the scene: component.parameter, clock.key, rig.key or a top-level key\n"
    "(seed, domain_id, ...). Repeatable; applied in the order given.";

// CLI11's help, laid out as uampc's always was: a synopsis per command ("uampc launch SCENE.yaml
// [--set NAME=VALUE ...] [--out DIR]") above its description, where CLI11 would print
// "Usage: uampc launch [OPTIONS] SCENE.yaml".
class SynopsisFormatter : public CLI::Formatter {
 public:
  // A line break in a synopsis continues it under its first argument.
  void addSynopsis(const std::string& command, const std::string& synopsis) { synopses_[command] = synopsis; }

  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    return make_usage(app, name) + make_description(app) + make_positionals(app) + make_groups(app, mode) +
           make_subcommands(app, mode) + "\n" + make_footer(app);
  }

  std::string make_usage(const CLI::App* app, std::string) const override {
    if (app->get_parent() == nullptr) {
      return "usage: uampc COMMAND ...   (uampc COMMAND --help describes a command and its options)\n";
    }
    return "usage: " + synopsis(*app, "usage: ") + "\n";
  }

  std::string make_subcommand(const CLI::App* sub) const override {
    return "  " + synopsis(*sub, "  ") + "\n" + indented(sub->get_description(), "      ") + "\n";
  }

 private:
  std::string synopsis(const CLI::App& command, const std::string& prefix) const {
    const auto found = synopses_.find(command.get_name());
    const std::string text = found == synopses_.end() ? "uampc " + command.get_name() : found->second;
    const std::string continuation = "\n" + std::string(prefix.size() + command.get_name().size() + 7, ' ');
    return CLI::detail::find_and_replace(text, "\n", continuation);
  }

  static std::string indented(const std::string& text, const std::string& indent) {
    return indent + CLI::detail::find_and_replace(text, "\n", "\n" + indent);
  }

  std::map<std::string, std::string> synopses_;
};

// Everything the command line sets; each command reads its part.
struct CommandLine {
  uampc::LaunchOptions scene;                // launch, validate, graph, run-process, clock
  std::vector<std::string> overrides;        // --set, as given, parsed into scene.overrides
  std::string process;                       // run-process
  bool own_clock = false;                    // run-process
  std::string graph_format = "mermaid";      // graph
  bool json = false;                         // components
  bool markdown = false;                     // components
  uampc::app::ExperimentOptions experiment;  // experiment
  uampc::app::TopicOptions topic;            // topic
  uampc::app::PlayOptions play;              // play
  uampc::app::RecordOptions record;          // record
  uampc::app::ViewOptions view;              // view
  uampc::app::SecurityInitOptions security;  // security init
};

// A command: its subcommand in the app and what runs when it was given.
struct Command {
  CLI::App* app;
  std::function<int()> run;
};

class UampcCli {
 public:
  UampcCli() {
    app_.formatter(formatter_);  // before the subcommands: they copy their parent's formatter
    app_.set_help_flag("-h,--help", "Print this help and exit");
    app_.set_version_flag("--version", uampc::app::versionText,
                          "Print uampc's version (git describe when it was built) and Fast DDS's, and exit");
    app_.require_subcommand(1);
    app_.footer(kFooter);
    addLaunch();
    addValidate();
    addGraph();
    addExperiment();
    addComponents();
    addRunProcess();
    addClock();
    addTopic();
    addRecord();
    addPlay();
    addView();
    addSecurity();
  }

  int run(int argc, char** argv) {
    if (argc < 2) {
      std::cout << app_.help();
      return kCommandLineError;
    }
    // CLI11 would say "A subcommand is required"; name what it got instead.
    const std::string first = argv[1];
    bool known = app_.get_option_no_throw(first) != nullptr;
    for (const Command& c : commands_) known = known || c.app->get_name() == first;
    if (!known) {
      return commandLineError(nullptr,
                              (first.rfind('-', 0) == 0 ? "unknown option '" : "unknown command '") + first + "'");
    }
    try {
      app_.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app_.exit(e);  // --help, --version
      return commandLineError(given(), e.what());
    }
    const Command* command = given();
    return command ? command->run() : commandLineError(nullptr, "no command given");
  }

 private:
  CLI::App* addCommand(const std::string& name, const std::string& synopsis, const std::string& description) {
    formatter_->addSynopsis(name, synopsis);
    CLI::App* sub = app_.add_subcommand(name, description);
    sub->group("Commands");
    return sub;
  }

  void addScene(CLI::App* sub) {
    sub->add_option("SCENE.yaml", options_.scene.scene_path, "The scene file.")->required()->type_name("");
  }

  void addOverrides(CLI::App* sub) {
    sub->add_option("--set", options_.overrides, kSetHelp)->allow_extra_args(false)->type_name("NAME=VALUE");
  }

  void addOutput(CLI::App* sub) {
    sub->add_option("--out", options_.scene.output_directory, "Collect the run's outputs in DIR.")->type_name("DIR");
  }

  // The scene commands: their --set values parsed as the scene loader reads them, then the command.
  std::function<int()> withOverrides(std::function<int()> command) {
    return [this, command] {
      try {
        for (const std::string& text : options_.overrides)
          options_.scene.overrides.push_back(uampc::parseOverride(text));
      } catch (const uampc::SceneError& e) {
        return commandLineError(given(), e.what());
      }
      return command();
    };
  }

  void addLaunch() {
    CLI::App* sub =
        addCommand("launch",
                   "uampc launch SCENE.yaml [--set NAME=VALUE ...] [--out DIR [--overwrite]]\n"
                   "[--view [--view-port P] [--view-address A]]",
                   "Validate and run a scene. NAME is component.parameter, clock.key or a top-level key\n"
                   "(seed, domain_id, ...). --out DIR collects the run's outputs, with DIR/scene.yaml (the\n"
                   "resolved scene: launch it to run the same again) and DIR/run_info.json (scene, overrides,\n"
                   "seed, versions, every parameter; also in DIR/metrics.json as \"run\"); a DIR that holds a run\n"
                   "already is refused unless --overwrite is given. Ctrl-C stops\n"
                   "everything, while starting or running (exit code 130). --view serves the run live to Foxglove\n"
                   "(docs/user/viewing.md).");
    addScene(sub);
    addOverrides(sub);
    addOutput(sub);
    sub->add_flag("--overwrite", options_.scene.overwrite,
                  "Write into --out DIR even if it holds a run already (its run_info.json or metrics.json);\n"
                  "files the new run does not write are left as they are.");
    addViewer(sub, options_.scene.viewer);
    commands_.push_back({sub, withOverrides([this] {
                           options_.scene.uampc_version = uampc::app::uampcVersion();  // for the run's record
                           options_.scene.fastdds_version = uampc::app::fastDdsVersion();
                           return uampc::launch(options_.scene);
                         })});
  }

  void addValidate() {
    CLI::App* sub = addCommand("validate", "uampc validate SCENE.yaml [--set NAME=VALUE ...]",
                               "Only validate the scene; print every problem with file:line:column.");
    addScene(sub);
    addOverrides(sub);
    commands_.push_back({sub, withOverrides([this] { return uampc::app::validateCommand(options_.scene); })});
  }

  void addGraph() {
    CLI::App* sub =
        addCommand("graph", "uampc graph SCENE.yaml [--set NAME=VALUE ...] [--format mermaid|dot]",
                   "Print the scene's resolved graph (components, and the topics between them with their types)\n"
                   "as a Mermaid flowchart (default) or Graphviz DOT.");
    addScene(sub);
    addOverrides(sub);
    sub->add_option("--format", options_.graph_format, "mermaid (default) or dot.")
        ->check(CLI::IsMember({"mermaid", "dot"}).description(""))
        ->type_name("mermaid|dot");
    commands_.push_back({sub, withOverrides([this] {
                           const auto format = options_.graph_format == "dot" ? uampc::app::GraphFormat::kDot
                                                                              : uampc::app::GraphFormat::kMermaid;
                           return uampc::app::graphCommand(options_.scene, format);
                         })});
  }

  void addExperiment() {
    using uampc::app::kHighestDomainId;
    uampc::app::ExperimentOptions& o = options_.experiment;
    CLI::App* sub =
        addCommand("experiment",
                   "uampc experiment EXPERIMENT.yaml --out DIR [--jobs N] [--data-dir DIR] [--domain-base N]\n"
                   "[--set NAME=VALUE ...] [--dry-run | --plan-only] [--backend local|slurm [--partition P] [--time T] [--no-wait]]\n"
                   "uampc experiment --collect DIR\n"
                   "uampc experiment --run-task K --out DIR [--domain-base N]",
                   "Run every scene x controller x seed of an experiment (at most N at once, default: one per\n"
                   "CPU, each on DDS domain domain-base (100) + its slot), then write DIR/results.json,\n"
                   "DIR/results.md (the paper's table) and DIR/report/index.html. Finished runs are kept:\n"
                   "running it again only runs what is missing or failed. ${data_dir} in the experiment's\n"
                   "overrides is --data-dir. --set applies to every run. --dry-run only validates and lists the runs.\n"
                   "--backend slurm submits the unfinished runs as one Slurm job array instead (DIR on a filesystem\n"
                   "the nodes share), watches it and collects; --collect DIR builds the results from DIR's run\n"
                   "directories wherever they ran; --run-task K runs planned run K of DIR (what an array task does).");
    sub->add_option("EXPERIMENT.yaml", o.experiment_file, "The experiment file.")->type_name("");
    sub->add_option("--out", o.output_directory, "Write the runs, results and report into DIR.")->type_name("DIR");
    sub->add_option(
           "--jobs", o.jobs,
           "Run at most N (1 to " + std::to_string(uampc::app::kMostJobs) + ") at once (default: one per CPU).")
        ->check(CLI::Range(1, uampc::app::kMostJobs).description(""))
        ->type_name("N");
    sub->add_option("--data-dir", o.data_directory, "What ${data_dir} in the experiment's overrides stands for.")
        ->type_name("DIR");
    sub->add_option("--domain-base", o.domain_base,
                    "The first run's DDS domain; slot k runs on N + k (default " +
                        std::to_string(uampc::app::kDefaultDomainBase) + ", at most " +
                        std::to_string(kHighestDomainId) +
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
    sub->add_option("--run-task", o.run_task, "Run planned run K of --out DIR (what a Slurm array task runs).")
        ->check(CLI::Range(0L, 1000000L).description(""))
        ->type_name("K");
    commands_.push_back({sub, [this] {
                           const std::string error = uampc::app::experimentOptionsError(options_.experiment);
                           if (!error.empty()) return commandLineError(given(), error);
                           return uampc::app::experimentCommand(options_.experiment);
                         }});
  }

  void addComponents() {
    CLI::App* sub = addCommand("components", "uampc components [--json | --markdown]",
                               "List installed component types with their ports and parameters.");
    CLI::Option* json = sub->add_flag("--json", options_.json, "Print them as JSON (for tools) instead of text.");
    sub->add_flag("--markdown", options_.markdown,
                  "Print them as the Markdown page docs/user/components.md (without the libraries' paths).")
        ->excludes(json);
    commands_.push_back({sub, [this] {
                           using uampc::app::ComponentListFormat;
                           return uampc::app::componentsCommand(options_.json       ? ComponentListFormat::kJson
                                                                : options_.markdown ? ComponentListFormat::kMarkdown
                                                                                    : ComponentListFormat::kText);
                         }});
  }

  void addRunProcess() {
    CLI::App* sub =
        addCommand("run-process",
                   "uampc run-process SCENE.yaml --process NAME [--own-clock] [--set NAME=VALUE ...] [--out DIR]",
                   "Run one process group of a scene (launch does this for every group; use it to spread a\n"
                   "scene over containers or hosts).");
    addScene(sub);
    sub->add_option("--process", options_.process, "The process group to run (a process: of the scene).")
        ->required()
        ->type_name("NAME");
    sub->add_flag("--own-clock", options_.own_clock,
                  "Step this process group itself, from the other groups' acknowledgements, instead of following "
                  "`uampc clock`: what launch passes to its children when clock.in_process is true; it then "
                  "follows their progress (without launch, run `uampc clock` and leave this out).");
    addOverrides(sub);
    addOutput(sub);
    commands_.push_back({sub, withOverrides([this] {
                           return uampc::runProcessCommand(options_.scene, options_.process, options_.own_clock);
                         })});
  }

  void addClock() {
    CLI::App* sub =
        addCommand("clock", "uampc clock SCENE.yaml [--set NAME=VALUE ...]",
                   "Run only the lockstep clock of a scene whose process groups were started with run-process.");
    addScene(sub);
    addOverrides(sub);
    commands_.push_back({sub, withOverrides([this] { return uampc::runClockCommand(options_.scene); })});
  }

  void addTopic() {
    CLI::App* sub =
        addCommand("topic", "uampc topic list|echo|hz|bw [TOPIC] [--domain N] ...",
                   "Look at the topics of a running system, from DDS discovery (uampc's and any other vendor's):\n"
                   "list them with their types, writers and readers; echo a topic's samples as YAML; measure its\n"
                   "rate (hz) or bandwidth (bw). uampc topic list|echo|hz|bw --help describes each.");
    uampc::app::addTopicSubcommands(*sub, options_.topic, [this](const std::string& name, const std::string& synopsis) {
      formatter_->addSynopsis(name, synopsis);
    });
    commands_.push_back({sub, [this] { return uampc::app::topicCommand(options_.topic); }});
  }

  void addRecord() {
    uampc::app::RecordOptions& o = options_.record;
    CLI::App* sub = addCommand(
        "record",
        "uampc record -o FILE.mcap [--overwrite] [--domain N] [--compression zstd|lz4|none]\n"
        "[--chunk-size BYTES] [--duration S] [--security DIR] [TOPIC ...]",
        "Record the topics of a running system (every ROS topic discovered on the domain, of uampc or any\n"
        "other DDS vendor, by default) to an MCAP file as rosbag2 writes it (Foxglove, ros2 bag, uampc play).\n"
        "Ctrl-C stops it and completes the file. Inside a scene, use the recorder component.");
    sub->add_option("-o,--output", o.output, "The file to write; an existing one only with --overwrite.")
        ->required()
        ->type_name("FILE.mcap");
    sub->add_flag("--overwrite", o.overwrite, "Replace -o FILE.mcap if it exists (without it, an existing file is refused).");
    sub->add_option("TOPIC", o.topics,
                    "Topics to record (default: all but the lockstep protocol's, /uampc/lockstep/...; name one to\n"
                    "record it).")
        ->type_name("");
    sub->add_option("--domain", o.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0).")
        ->check(CLI::Range(0, uampc::kMaxDomainId))
        ->type_name("N");
    sub->add_option("--compression", o.compression, "Chunk compression: zstd (default), lz4 or none.")
        ->check(CLI::IsMember({"zstd", "lz4", "none"}).description(""))
        ->type_name("zstd|lz4|none");
    sub->add_option("--chunk-size", o.chunk_size,
                    "Bytes of samples per chunk (default 4 MiB); a killed recorder loses at most the last three chunks.")
        ->check(CLI::Range(std::uint64_t{1024}, std::uint64_t{1} << 30))
        ->type_name("BYTES");
    sub->add_option("--duration", o.duration_s, "Stop after S seconds (default: at Ctrl-C).")
        ->check(uampc::command_line::kFiniteNonNegative)
        ->type_name("S");
    sub->add_option("--security", o.security_dir,
                    "Join a secured domain with the observer identity of DIR (uampc security init), which may\n"
                    "read every topic.")
        ->type_name("DIR");
    commands_.push_back({sub, [this] { return uampc::app::recordCommand(options_.record); }});
  }

  void addPlay() {
    uampc::app::PlayOptions& o = options_.play;
    CLI::App* sub = addCommand(
        "play",
        "uampc play FILE.mcap [--domain N] [--rate R] [--start S] [--topics TOPIC ...] [--loop]\n[--clock] "
        "[--wait-for-readers] [--restamp] [--security DIR] [--view [--view-port P] [--view-address A]]",
        "Publish a recording's samples (MCAP as rosbag2 and uampc's recorder write it) with their recorded\n"
        "timing, in real time; prints the cost of each topic's publishing at the end. Inside a lockstep scene,\n"
        "use the player component instead (config/scenes/replay_lo.yaml).");
    sub->add_option("FILE.mcap", o.file, "The recording.")->required()->type_name("");
    sub->add_option("--domain", o.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0).")
        ->check(CLI::Range(0, uampc::kMaxDomainId))
        ->type_name("N");
    sub->add_option("--rate", o.rate, "Playback speed: 2 plays twice as fast (default 1).")
        ->check(uampc::command_line::kFinite)
        ->check(CLI::Range(0.01, 100.0))
        ->type_name("R");
    sub->add_option("--start", o.start_s, "Skip the recording's first S seconds.")
        ->check(uampc::command_line::kFiniteNonNegative)
        ->type_name("S");
    sub->add_option("--topics", o.topics, "Play only these topics (default: all).")->type_name("TOPIC ...");
    sub->add_flag("--loop", o.loop, "Start over at the end, until Ctrl-C.");
    sub->add_flag("--clock", o.clock,
                  "Publish /clock (100 Hz) with the recording's time, as ros2 bag play --clock. A recorded /clock\n"
                  "and the lockstep protocol's topics (/uampc/lockstep/...) are never played.");
    sub->add_flag("--wait-for-readers", o.wait_for_readers,
                  "Start only once every played topic has a reader (else after 0.5 s), so that no sample goes\n"
                  "out before the system under test or a recorder hears it.");
    sub->add_flag("--restamp", o.restamp,
                  "Move every header stamp (and a PointCloud2's absolute point times) to the present, as if the\n"
                  "recording were happening now: for a real-time system that pairs the played samples with live ones\n"
                  "by stamp (a recorded LiDAR beside a live motor, docs/user/rig.md).");
    sub->add_option("--security", o.security_dir,
                    "Join a secured domain with the player identity of DIR (uampc security init), which may\n"
                    "publish every topic, the motor's commands too.")
        ->type_name("DIR");
    addViewer(sub, o.viewer);
    commands_.push_back({sub, [this] { return uampc::app::playCommand(options_.play); }});
  }

  // --view and its address, for launch and play: a `uampc view` beside the run.
  static void addViewer(CLI::App* sub, uampc::ViewerOptions& o) {
    sub->add_flag("--view", o.enabled,
                  "Serve the topics live to Foxglove (WebSocket, ws://127.0.0.1:8765; docs/user/viewing.md).");
    sub->add_option("--view-port", o.port, "The viewer's TCP port (default 8765).")
        ->check(CLI::Range(1, 65535))
        ->type_name("P");
    sub->add_option("--view-address", o.address,
                    "The address the viewer binds (default 127.0.0.1, this machine only; another address is\n"
                    "warned about: anyone who reaches it sees every topic).")
        ->type_name("A");
  }

  void addView() {
    uampc::app::ViewOptions& o = options_.view;
    CLI::App* sub = addCommand(
        "view", "uampc view [--domain N] [--port P] [--address A] [--security DIR] [--duration S]",
        "Serve what a DDS domain publishes (a rig, another machine's run, a replay) live to Foxglove over\n"
        "its WebSocket protocol: every ROS topic with its schema, read from DDS only while a client\n"
        "subscribes; the domain's /clock sets the clients' time. Ctrl-C stops it (docs/user/viewing.md).");
    sub->add_option("--domain", o.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0).")
        ->check(CLI::Range(0, uampc::kMaxDomainId))
        ->type_name("N");
    sub->add_option("--port", o.port, "TCP port (default 8765; 0: any free port, printed).")
        ->check(CLI::Range(0, 65535))
        ->type_name("P");
    sub->add_option("--address", o.address,
                    "Address to bind (default 127.0.0.1, this machine only; another address is warned about).")
        ->type_name("A");
    sub->add_option("--security", o.security_dir,
                    "Join a secured domain with the observer identity of DIR (uampc security init), which may\n"
                    "read every topic.")
        ->type_name("DIR");
    sub->add_option("--duration", o.duration_s, "Stop after S seconds (default: at Ctrl-C).")
        ->check(uampc::command_line::kFiniteNonNegative)
        ->type_name("S");
    commands_.push_back({sub, [this] { return uampc::app::viewCommand(options_.view); }});
  }

  void addSecurity() {
    uampc::app::SecurityInitOptions& o = options_.security;
    CLI::App* sub =
        addCommand("security", "uampc security init DIR --scene SCENE.yaml [--days N] [--sign-metadata]",
                   "DDS Security (authentication, encryption, permissions) for a scene's runs. 'init' makes\n"
                   "DIR with openssl: a CA, an identity per process of the scene and one for the launcher,\n"
                   "the governance and, per identity, permissions for exactly the topics its components read\n"
                   "and write, signed by the CA. Then run the scene with security: {directory: DIR}.");
    sub->require_subcommand(1);
    CLI::App* init = sub->add_subcommand("init", "Make the security directory DIR for a scene.");
    formatter_->addSynopsis("init", "uampc security init DIR --scene SCENE.yaml [--days N] [--sign-metadata]");
    init->add_option("DIR", o.directory, "The directory to make (must not hold one already).")
        ->required()
        ->type_name("");
    init->add_option("--scene", o.scene_path, "The scene whose processes and topics are granted.")
        ->required()
        ->type_name("SCENE.yaml");
    init->add_option("--days", o.days, "Validity of the certificates and permissions, days (default 365).")
        ->check(CLI::Range(1, 36500))
        ->type_name("N");
    init->add_flag("--sign-metadata", o.sign_metadata,
                   "Also sign every submessage around the samples (heartbeats, acknowledgements), so that an\n"
                   "outsider cannot disturb delivery; costs more CPU (docs/user/security.md, \"Cost\").");
    commands_.push_back({sub, [this] { return uampc::app::securityInitCommand(options_.security); }});
  }

  // The command on the command line, if CLI11 got as far as reading it.
  const Command* given() const {
    for (const Command& c : commands_) {
      if (c.app->parsed()) return &c;
    }
    return nullptr;
  }

  // "uampc launch: <message>", the command's synopsis and where to read more; exit code 2.
  int commandLineError(const Command* command, const std::string& message) const {
    const std::string name = command ? "uampc " + command->app->get_name() : "uampc";
    std::cerr << name << ": " << message << "\n";
    if (command) std::cerr << formatter_->make_usage(command->app, "");
    std::cerr << "(" << name << " --help for more)\n";
    return kCommandLineError;
  }

  std::shared_ptr<SynopsisFormatter> formatter_ = std::make_shared<SynopsisFormatter>();
  CLI::App app_{"", "uampc"};
  CommandLine options_;
  std::vector<Command> commands_;
};

}  // namespace

int main(int argc, char** argv) { return UampcCli().run(argc, argv); }
