// Runs that say what they were, and Ctrl-C (docs/user/experiments.md): `uampc launch --out DIR`
// writes the resolved scene (DIR/scene.yaml) that reproduces the run, metrics.json says which
// scene, seed, parameters and versions made it; Ctrl-C exits 130 whether the scene was still
// starting or running.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <thread>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/json_text.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_progress.hpp"
#include "uampc/runtime/run_record.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

ComponentCatalog installedComponents() { return ComponentCatalog({binaryPath("lib/uampc/components")}); }

void expectSameScene(const Scene& a, const Scene& b, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.domain_id, b.domain_id);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.dds_profile, b.dds_profile);
  EXPECT_EQ(a.on_crash, b.on_crash);
  EXPECT_EQ(a.max_restarts, b.max_restarts);
  EXPECT_EQ(a.clock.mode, b.clock.mode);
  EXPECT_EQ(a.clock.step.ns, b.clock.step.ns);
  EXPECT_EQ(a.clock.duration_s, b.clock.duration_s);
  EXPECT_EQ(a.clock.ack_timeout_s, b.clock.ack_timeout_s);
  EXPECT_EQ(a.clock.real_time_factor, b.clock.real_time_factor);
  EXPECT_EQ(a.rig, b.rig);
  ASSERT_EQ(a.components.size(), b.components.size());
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    const ComponentInstance& x = a.components[i];
    const ComponentInstance& y = b.components[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type) << x.name;
    EXPECT_EQ(x.process, y.process) << x.name;
    EXPECT_EQ(x.params, y.params) << x.name;
    EXPECT_EQ(x.topics, y.topics) << x.name;
  }
}

// `uampc --version`'s two lines, without their names.
std::pair<std::string, std::string> versions() {
  const CommandResult r = runUampc("--version");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::istringstream lines(r.output);
  std::string uampc, fastdds;
  std::getline(lines, uampc);
  std::getline(lines, fastdds);
  EXPECT_EQ(uampc.rfind("uampc ", 0), 0u) << r.output;
  EXPECT_EQ(fastdds.rfind("Fast DDS ", 0), 0u) << r.output;
  return {uampc.substr(6), fastdds.substr(9)};
}

// The resolved text of a scene, loaded, is the same scene; written again, the same text.
void expectResolvedRoundTrip(const Scene& original, const std::string& name, ComponentCatalog& catalog) {
  const std::string text = resolvedSceneYaml(original);
  const std::string copy = freshDirectory("resolved_" + name) + "/scene.yaml";
  std::ofstream(copy) << text;
  const Scene reloaded = loadScene(copy, {}, catalog);
  expectSameScene(original, reloaded, name);
  EXPECT_EQ(resolvedSceneYaml(reloaded), text) << name;
}

TEST(RunRecord, EveryShippedSceneResolvedLoadsBackAsTheSameScene) {
  // Without running anything, with overrides of every kind.
  const std::vector<Override> overrides = {parseOverride("seed=5"), parseOverride("clock.duration=3.25"),
                                           parseOverride("domain_id=7")};
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(sourcePath("config/scenes"))) {
    if (entry.path().extension() != ".yaml") continue;
    ComponentCatalog catalog = installedComponents();
    Scene original;
    try {
      original = loadScene(entry.path().string(), overrides, catalog);
    } catch (const SceneError& e) {
      // Not this test's: a scene that needs a value given (replay_lo.yaml: the recording).
      std::cout << entry.path().filename().string() << " does not load as it is; left out: " << e.what() << "\n";
      continue;
    }
    expectResolvedRoundTrip(original, entry.path().stem().string(), catalog);
    ++scenes;
  }
  EXPECT_GE(scenes, 9);  // the simulator and closed-loop scenes at least
}

TEST(RunRecord, RemappedTopicsProcessesAndAwkwardStringsSurviveTheCopy) {
  const std::string scene = freshDirectory("resolved_remapped_source") + "/remapped.yaml";
  std::ofstream(scene) << R"(name: "remapped: #1"
clock: {mode: realtime, duration: 0, real_time_factor: 1}
on_crash: restart
max_restarts: 5
components:
  controller:
    type: constant_speed_controller
    process: control
    params: {speed: -0.1}
    topics: {command: /cmd/speed}
  motor:
    type: motor_bridge
    params: {joint_name: "a 'joint': [1], # not a comment", encoder_rate: 1e3}
    topics: {command: controller/command}
)";
  ComponentCatalog catalog = installedComponents();
  const Scene original = loadScene(scene, {}, catalog);
  ASSERT_EQ(original.find("motor")->topics.at("command"), "/cmd/speed");
  expectResolvedRoundTrip(original, "remapped", catalog);
}

// One short lockstep run of the closed loop, shared by the tests below.
struct RecordedRun {
  std::string directory;
  std::string scene = sourcePath("config/scenes/campus_ua_mpc.yaml");
  std::vector<std::string> overrides = {"clock.duration=2",
                                        "domain_id=" + std::to_string(testDomain(DomainBlock::kRunInfo, 0)), "seed=7",
                                        "controller.alpha=500"};
};

const RecordedRun& recordedRun() {
  static const RecordedRun run = [] {
    RecordedRun r;
    r.directory = freshDirectory("run_info_original");
    std::string command = "launch " + r.scene + " --out " + r.directory;
    for (const auto& o : r.overrides) command += " --set " + o;
    const CommandResult result = runUampc(command);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return r;
  }();
  return run;
}

TEST(RunRecord, TheRunDirectoryHoldsTheResolvedSceneAsValidYamlThatLoads) {
  const RecordedRun& run = recordedRun();
  const std::string copy = run_files::inDirectory(run.directory, run_files::kSceneCopyFile);
  ASSERT_TRUE(fs::is_regular_file(copy));
  const YAML::Node yaml = YAML::LoadFile(copy);  // throws if it is not YAML
  ASSERT_TRUE(yaml.IsMap());
  EXPECT_EQ(yaml["seed"].as<int>(), 7);
  EXPECT_EQ(yaml["components"]["controller"]["params"]["alpha"].as<double>(), 500.0);
  // Defaults are written out: the controller's horizon was never set by the scene.
  EXPECT_TRUE(yaml["components"]["controller"]["params"]["horizon"]);

  ComponentCatalog catalog = installedComponents();
  std::vector<Override> overrides;
  for (const auto& o : run.overrides) overrides.push_back(parseOverride(o));
  expectSameScene(loadScene(run.scene, overrides, catalog), loadScene(copy, {}, catalog), "the run's copy");
}

TEST(RunRecord, MetricsSayWhichSceneSeedParametersAndVersionsMadeTheRun) {
  const RecordedRun& run = recordedRun();
  const auto metrics = run_files::readMetricsFile(run_files::inDirectory(run.directory, run_files::kMetricsFile));
  ASSERT_TRUE(metrics);
  ASSERT_TRUE(metrics->run) << "metrics.json has no whole \"run\" object";
  const run_files::RunInfo& info = *metrics->run;
  EXPECT_EQ(info.scene_copy, "scene.yaml");
  EXPECT_EQ(info.scene_source, run.scene);
  EXPECT_EQ(info.overrides, run.overrides);
  EXPECT_EQ(info.seed, 7u);  // the --set seed, not the scene file's 1
  EXPECT_EQ(info.domain_id, testDomain(DomainBlock::kRunInfo, 0));
  const auto [uampc_version, fastdds_version] = versions();
  EXPECT_FALSE(info.uampc_version.empty());
  EXPECT_EQ(info.uampc_version, uampc_version);
  EXPECT_EQ(info.fastdds_version, fastdds_version);
  // Every parameter of every component, as the scene resolved them.
  ComponentCatalog catalog = installedComponents();
  const Scene scene = loadScene(run_files::inDirectory(run.directory, run_files::kSceneCopyFile), {}, catalog);
  ASSERT_EQ(info.components.size(), scene.components.size());
  for (const ComponentInstance& c : scene.components) {
    ASSERT_TRUE(info.components.contains(c.name)) << c.name;
    const run_files::Json& recorded = info.components[c.name];
    EXPECT_EQ(recorded["type"], c.type);
    EXPECT_EQ(recorded["params"].size(), c.params.size()) << c.name;
  }
  EXPECT_EQ(info.components["controller"]["params"]["alpha"].get<double>(), 500.0);
  EXPECT_EQ(info.components["lidar"]["params"]["tilt_deg"].get<double>(), 30.0);  // rig values too
}

TEST(RunRecord, UncertaintyCsvIsRectangular) {
  const std::string path = run_files::inDirectory(recordedRun().directory, run_files::kUncertaintyFile);
  std::ifstream in(path);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
  const auto header = fields(line);
  EXPECT_EQ(header, 4 + 72);  // time, theta_start, delta_theta, command and 5-degree samples
  int rows = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(fields(line), header) << path << ":" << rows + 2;
    ++rows;
  }
  EXPECT_GT(rows, 10);
}

TEST(RunRecord, LaunchingTheCopyReproducesTheRun) {
  const RecordedRun& run = recordedRun();
  const std::string again = freshDirectory("run_info_again");
  const CommandResult r =
      runUampc("launch " + run_files::inDirectory(run.directory, run_files::kSceneCopyFile) + " --out " + again);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(run.directory)) {
    const std::string name = entry.path().filename().string();
    // Measured computation times, and the record of where the run came from, differ.
    if (name == run_files::kTimingsFile || name == run_files::kRunInfoFile || name == run_files::kMetricsFile) continue;
    EXPECT_EQ(readFile(entry.path().string()), readFile(run_files::inDirectory(again, name))) << name;
    ++compared;
  }
  EXPECT_GE(compared, 9);  // scene.yaml (the copy of the copy is the copy), the CSVs, trajectories, voxels
  // metrics.json byte for byte, but for the run object.
  run_files::Json first = run_files::readJsonFile(run_files::inDirectory(run.directory, run_files::kMetricsFile));
  run_files::Json second = run_files::readJsonFile(run_files::inDirectory(again, run_files::kMetricsFile));
  EXPECT_EQ(second["run"]["scene_source"], run_files::inDirectory(run.directory, run_files::kSceneCopyFile));
  EXPECT_EQ(second["run"]["components"], first["run"]["components"]);
  first.erase("run");
  second.erase("run");
  EXPECT_EQ(run_files::dumpJson(first), run_files::dumpJson(second));
}

// ---------------------------------------------------------------- Ctrl-C

TEST(CtrlC, WhileTheProcessesAreStartingExits130) {
  const std::string dir = freshDirectory("ctrl_c_starting");
  const std::string gate = dir + "/gate", log = dir + "/launch.log";
  const pid_t pid = startLaunch(sourcePath("tests/scenes/start_gate.yaml") + domainOverride(DomainBlock::kRunInfo, 1) +
                                    " --set gate.file=" + gate,
                                log);
  // Process 'main' cannot finish starting while 'gated' waits for the gate; it says so after 2 s.
  ASSERT_TRUE(waitFor([&] { return logHas(log, "starting: waiting for"); }, std::chrono::seconds(30))) << readFile(log);
  kill(-pid, SIGINT);             // Ctrl-C in a terminal: to the launcher and its processes
  std::ofstream(gate) << "open";  // the gated process then sees that it is to stop
  EXPECT_EQ(exitCodeOf(pid), 130) << readFile(log);
  const std::string output = readFile(log);
  EXPECT_NE(output.find("stopped by Ctrl-C"), std::string::npos) << output;
  EXPECT_EQ(output.find("run failed"), std::string::npos) << output;
  EXPECT_EQ(output.find("while stopping"), std::string::npos) << output;  // every process ended cleanly
}

TEST(CtrlC, WhileALockstepRunRunsExits130) {
  const std::string dir = freshDirectory("ctrl_c_running");
  const std::string gate = dir + "/gate", log = dir + "/launch.log", progress = dir + "/progress.json";
  std::ofstream(gate) << "open";
  const pid_t pid = startLaunch(sourcePath("tests/scenes/start_gate.yaml") + domainOverride(DomainBlock::kRunInfo, 2) +
                                    " --set gate.file=" + gate,
                                log, std::string(run_files::kProgressFileVariable) + "=" + progress);
  ASSERT_TRUE(waitFor(
      [&] {
        const auto p = run_files::readRunProgress(progress);
        return p && p->sim_s > 0.0;
      },
      std::chrono::seconds(30)))
      << readFile(log);
  kill(-pid, SIGINT);
  EXPECT_EQ(exitCodeOf(pid), 130) << readFile(log);
  const std::string output = readFile(log);
  EXPECT_NE(output.find("stopped by Ctrl-C"), std::string::npos) << output;
  EXPECT_EQ(output.find("while stopping"), std::string::npos) << output;
}

}  // namespace
}  // namespace uampc::test
