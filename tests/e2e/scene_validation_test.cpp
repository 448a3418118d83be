// Every invalid scene in tests/scenes/invalid/ is refused before anything starts, with a non-zero
// exit and the message its first line announces ("# expect: LINE:COLUMN: error: text"), prefixed
// by the scene's path.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/runtime/component.hpp"
#include "uampc/runtime/component_library.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc::test {
namespace {

struct InvalidScene {
  std::string path;
  std::string expected;  // "path:line:column: error: ..."
};

std::vector<InvalidScene> invalidScenes() {
  std::vector<InvalidScene> scenes;
  for (const auto& entry : std::filesystem::directory_iterator(sourcePath("tests/scenes/invalid"))) {
    std::ifstream in(entry.path());
    std::string first;
    std::getline(in, first);
    const std::string tag = "# expect: ";
    if (first.rfind(tag, 0) != 0) continue;
    scenes.push_back({entry.path().string(), entry.path().string() + ":" + first.substr(tag.size())});
  }
  std::sort(scenes.begin(), scenes.end(), [](auto& a, auto& b) { return a.path < b.path; });
  return scenes;
}

TEST(SceneValidation, EveryInvalidSceneIsRefusedWithFileLineAndColumn) {
  const auto scenes = invalidScenes();
  ASSERT_GE(scenes.size(), 11u);
  for (const auto& scene : scenes) {
    SCOPED_TRACE(scene.path);
    const CommandResult validate = runUampc("validate " + scene.path);
    EXPECT_EQ(validate.exit_code, 2) << validate.output;
    EXPECT_NE(validate.output.find(scene.expected), std::string::npos)
        << "expected: " << scene.expected << "\ngot: " << validate.output;
  }
}

TEST(SceneValidation, LaunchRefusesAnInvalidSceneBeforeStartingAnything) {
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/invalid/unknown_parameter.yaml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("nothing was started"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("uampc: scene"), std::string::npos) << r.output;
}

TEST(SceneValidation, CommandLineOverridesAreValidatedAndNamed) {
  const std::string scene = sourcePath("config/scenes/default.yaml");
  CommandResult r = runUampc("validate " + scene + " --set motor.encoder_rate=abc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--set motor.encoder_rate=abc: error: parameter 'encoder_rate'"), std::string::npos)
      << r.output;
  r = runUampc("validate " + scene + " --set nobody.speed=1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("the scene has no component 'nobody'"), std::string::npos) << r.output;
  // A key --set cannot set names those it can.
  r = runUampc("validate " + scene + " --set 'unused_inputs=[/lo/imu]'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("a top-level key (dds_profile, domain_id, max_restarts, name, on_crash, security, seed); "
                          "the topic lists are set in the scene file"),
            std::string::npos)
      << r.output;
  r = runUampc("validate " + scene + " --set controller.speed=1.8");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--set controller.speed=1.8: error: unknown parameter 'speed' for component 'controller' "
                          "(mpc)"),
            std::string::npos)
      << r.output;
  r = runUampc("validate " + scene + " --set controller.constant_speed=1.8 --set clock.duration=2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(SceneValidation, AllProblemsOfAFileAreReportedInOneRun) {
  const std::string dir = freshDirectory("validation_many");
  const std::string path = dir + "/many.yaml";
  std::ofstream(path) << "clock: {mode: sometimes}\ncomponents:\n  motor:\n    type: motor_bridge\n"
                         "    params: {encoder_rate: 0, speeed: 1}\n";
  const CommandResult r = runUampc("validate " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(path + ":1:15: error: clock.mode must be 'lockstep' or 'realtime'"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(path + ":5:28: error: parameter 'encoder_rate'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(path + ":5:31: error: unknown parameter 'speeed'"), std::string::npos) << r.output;
}

TEST(SceneValidation, ShippedScenesAreValid) {
  for (const auto& entry : std::filesystem::directory_iterator(sourcePath("config/scenes"))) {
    if (entry.path().extension() != ".yaml") continue;
    // replay_lo names no recording: valid once one is given (record_replay_test), refused until then.
    const bool needs_recording = entry.path().filename() == "replay_lo.yaml";
    const CommandResult r = runUampc("validate " + entry.path().string());
    EXPECT_EQ(r.exit_code, needs_recording ? 2 : 0) << entry.path() << "\n" << r.output;
    if (needs_recording) {
      EXPECT_NE(r.output.find("missing required parameter 'file'"), std::string::npos) << r.output;
    }
  }
}

// Writes `text` to DIR/NAME and returns the path.
std::string writeScene(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// Two writers of a topic that needs one are an error (tests/scenes/invalid/two_motor_commands.yaml);
// of any other topic, a warning: two motor bridges' /motor/state is an error, two evaluators'
// /evaluator/metrics only interleave. Before, both passed validation silently.
TEST(SceneValidation, TwoWritersOfOneTopicAreAnErrorOrAWarning) {
  const std::string dir = freshDirectory("validation_two_writers");
  const std::string two_worlds = writeScene(dir, "two_worlds.yaml",
                                            "components:\n  a:\n    type: map_provider\n  b:\n    type: map_provider\n");
  CommandResult r = runUampc("validate " + two_worlds);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("2 components write /ground_truth/pose: a.ground_truth, b.ground_truth"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("2 components write /world/mesh"), std::string::npos) << r.output;
  const std::string two_evaluators = writeScene(
      dir, "two_evaluators.yaml", "components:\n  e1:\n    type: evaluator\n  e2:\n    type: evaluator\n");
  r = runUampc("validate " + two_evaluators);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("warning: 2 components write /evaluator/metrics: e1.metrics, e2.metrics"), std::string::npos)
      << r.output;
}

TEST(SceneValidation, PortReferenceChainsResolveToTheirEndInAnyOrder) {
  // Four references in a row, written top-down and bottom-up: every reader ends on the motor's
  // /enc/state (one pass in file order left evaluator on lo's default topic).
  const std::string dir = freshDirectory("validation_chain");
  const std::vector<std::string> links = {
      "  evaluator:\n    type: evaluator\n    topics: {motor_state: lo/motor_state}\n",
      "  lo:\n    type: lo\n    topics: {motor_state: controller/motor_state}\n",
      "  controller:\n    type: mpc\n    topics: {motor_state: lidar/motor_state}\n",
      "  lidar:\n    type: raycaster\n    topics: {motor_state: motor/state}\n",
      "  motor:\n    type: motor_bridge\n    topics: {state: /enc/state}\n"};
  std::string top_down = "components:\n", bottom_up = "components:\n";
  for (std::size_t i = 0; i < links.size(); ++i) {
    top_down += links[i];
    bottom_up += links[links.size() - 1 - i];
  }
  for (const auto& path : {writeScene(dir, "top_down.yaml", top_down), writeScene(dir, "bottom_up.yaml", bottom_up)}) {
    SCOPED_TRACE(path);
    const CommandResult r = runUampc("graph " + path + " --format dot");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const char* reader : {"c_lidar", "c_controller", "c_lo", "c_evaluator"}) {
      EXPECT_NE(
          r.output.find(std::string("c_motor -> ") + reader + " [label=\"/enc/state\\nsensor_msgs/msg/JointState\"]"),
          std::string::npos)
          << reader << "\n"
          << r.output;
    }
    EXPECT_EQ(r.output.find("/motor/state"), std::string::npos) << r.output;
  }
}

TEST(SceneValidation, APortReferenceCycleNamesEveryLink) {
  const std::string path = sourcePath("tests/scenes/invalid/port_reference_cycle.yaml");
  const CommandResult r = runUampc("validate " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(path +
                          ":5:27: error: port references form a cycle, so none of them has a topic: "
                          "lo.motor_state = controller/motor_state (" +
                          path + ":5:27), controller.motor_state = lo/motor_state (" + path + ":8:27)"),
            std::string::npos)
      << r.output;
  // The ports left on their default topics are not reported as well.
  EXPECT_EQ(r.output.find("no component in the scene writes"), std::string::npos) << r.output;
}

TEST(SceneValidation, SilentPortsAreWarningsOneLinePerTopicWithASuggestion) {
  const std::string dir = freshDirectory("validation_silent");
  const std::string path = writeScene(dir, "silent.yaml",
                                      "components:\n"
                                      "  motor:\n    type: motor_bridge\n    topics: {state: /motor/stat}\n"
                                      "  lo:\n    type: lo\n"
                                      "  controller:\n    type: mpc\n");
  const CommandResult r = runUampc("validate " + path);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // Both readers of /motor/state on their default topic: one warning, with the near miss.
  EXPECT_NE(r.output.find(path + ":5:3: warning: no component in the scene writes /motor/state, read by "
                                 "lo.motor_state, controller.motor_state (sensor_msgs/msg/JointState); did you "
                                 "mean '/motor/stat'?"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(path + ":4:21: warning: nobody in the scene reads /motor/stat, written by motor.state "
                                 "(sensor_msgs/msg/JointState); did you mean '/motor/state'?"),
            std::string::npos)
      << r.output;
  std::size_t lines_about_motor_state = 0;
  for (std::size_t at = r.output.find("writes /motor/state,"); at != std::string::npos;
       at = r.output.find("writes /motor/state,", at + 1)) {
    ++lines_about_motor_state;
  }
  EXPECT_EQ(lines_about_motor_state, 1u) << r.output;
  // Launch prints them too, before it starts anything.
  const std::string motor_only = writeScene(
      dir, "motor_only.yaml",
      "clock: {duration: 0.01}\ncomponents:\n  motor:\n    type: motor_bridge\n    topics: {state: /motor/stat}\n");
  const CommandResult launch = runUampc("launch " + motor_only + domainOverride(DomainBlock::kSceneValidation, 0));
  EXPECT_EQ(launch.exit_code, 0) << launch.output;
  EXPECT_NE(launch.output.find(motor_only + ":5:21: warning: nobody in the scene reads /motor/stat, written by "
                                            "motor.state"),
            std::string::npos)
      << launch.output;
}

// Every shipped scene validates without a warning: outputs for viewers (TF, the world's points,
// running metrics) that nobody in the scene reads are expected, and the scenes declare the rest
// (external_topics, unused_inputs, outputs_for_tools); the same topic from an output not for
// viewers still warns (above). replay_lo needs a recording: record_replay_test checks it on one;
// loop_test and rig_scene_test check that the scenes also start without one.
TEST(SceneValidation, ShippedScenesValidateWithoutWarnings) {
  std::size_t scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(sourcePath("config/scenes"))) {
    if (entry.path().extension() != ".yaml" || entry.path().filename() == "replay_lo.yaml") continue;
    ++scenes;
    const CommandResult r = runUampc("validate " + entry.path().string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << entry.path() << ":\n" << r.output;
  }
  EXPECT_GE(scenes, 14u);
}

// The shipped scenes name no DDS domain (default.yaml pinned 0): each runs on ROS_DOMAIN_ID when it
// is set, as a ROS 2 user expects, else on 0; --set domain_id=N still wins (docs/user/scenes.md).
TEST(SceneValidation, ShippedScenesRunOnRosDomainIdUnlessDomainIdIsSet) {
  const std::string ros_domain = std::to_string(testDomain(DomainBlock::kSceneValidation, 1));
  const std::string uampc = "ROS_DOMAIN_ID=" + ros_domain + " " + binaryPath("bin/uampc");
  const CommandResult r =
      runShell(uampc + " launch " + sourcePath("config/scenes/default.yaml") + " --set clock.duration=0.05");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("lockstep, DDS domain " + ros_domain + ")"), std::string::npos) << r.output;
  const std::string set_domain = std::to_string(testDomain(DomainBlock::kSceneValidation, 2));
  const CommandResult set = runShell(uampc + " launch " + sourcePath("config/scenes/default_split.yaml") +
                                     " --set clock.duration=0.05 --set domain_id=" + set_domain);
  EXPECT_EQ(set.exit_code, 0) << set.output;
  EXPECT_NE(set.output.find("lockstep, DDS domain " + set_domain + ")"), std::string::npos) << set.output;
  // Every other shipped scene the same, loaded as launch loads it (replay_lo.yaml needs a recording
  // to load: its file is read below).
  ASSERT_EQ(setenv("ROS_DOMAIN_ID", ros_domain.c_str(), 1), 0);
  ComponentCatalog catalog({binaryPath("lib/uampc/components")});
  for (const auto& entry : std::filesystem::directory_iterator(sourcePath("config/scenes"))) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_EQ(readFile(entry.path().string()).find("\ndomain_id:"), std::string::npos) << entry.path();
    if (entry.path().filename() == "replay_lo.yaml") continue;
    EXPECT_EQ(loadScene(entry.path().string(), {}, catalog).domain_id, std::stoi(ros_domain)) << entry.path();
  }
  unsetenv("ROS_DOMAIN_ID");
}

TEST(SceneValidation, GraphPrintsMermaidByDefault) {
  const CommandResult r = runUampc("graph " + sourcePath("config/scenes/default_split.yaml"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("flowchart LR"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("c_motor[\"motor<br/>motor_bridge<br/>process motor\"]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("c_controller -->|\"/motor/command<br/>uampc/msg/MotorCommand\"| c_motor"), std::string::npos)
      << r.output;
  // Nobody reads the motor's state in this scene: the topic is drawn on its own, dashed.
  EXPECT_NE(r.output.find("(no reader)"), std::string::npos) << r.output;
  EXPECT_EQ(runUampc("graph " + sourcePath("config/scenes/default_split.yaml") + " --format svg").exit_code, 2);
}

TEST(SceneValidation, ExtendsMergesComponentsKeyByKeyAndNamesTheFileOfEachMistake) {
  const std::string dir = freshDirectory("validation_extends");
  std::filesystem::create_directories(dir + "/base");
  const std::string base = writeScene(dir, "base/base.yaml",
                                      "seed: 3\nclock: {mode: lockstep, step: 0.005}\ncomponents:\n"
                                      "  motor:\n    type: motor_bridge\n    params: {encoder_rate: 0, max_speed: 5}\n"
                                      "  controller:\n    type: constant_speed_controller\n    params: {speed: 1}\n");
  // A mistake in the base is reported at the base's line, one in the scene at the scene's.
  const std::string bad =
      writeScene(dir, "bad.yaml", "extends: base/base.yaml\ncomponents:\n  controller:\n    params: {speeed: 2}\n");
  CommandResult r = runUampc("validate " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(base + ":6:28: error: parameter 'encoder_rate'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(bad + ":4:14: error: unknown parameter 'speeed'"), std::string::npos) << r.output;
  // One parameter of one component changed, and a process: the rest of the base stays.
  const std::string good = writeScene(dir, "good.yaml",
                                      "extends: base/base.yaml\nclock: {duration: 1}\ncomponents:\n"
                                      "  motor:\n    params: {encoder_rate: 100}\n"
                                      "  controller:\n    process: control\n");
  r = runUampc("graph " + good + " --format dot");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("c_controller [label=\"controller\\nconstant_speed_controller\\nprocess control\"]"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("c_motor [label=\"motor\\nmotor_bridge\\nprocess main\"]"), std::string::npos) << r.output;
  // Chains: a scene that extends the one above still has the base's bounds checked where written.
  const std::string chained =
      writeScene(dir, "chained.yaml", "extends: good.yaml\ncomponents:\n  motor:\n    params: {max_speed: -1}\n");
  r = runUampc("validate " + chained);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(chained + ":4:25: error: parameter 'max_speed'"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("encoder_rate"), std::string::npos) << r.output;
  // Cycles are refused where they close.
  const std::string a = writeScene(dir, "a.yaml", "extends: b.yaml\ncomponents: {}\n");
  const std::string b = writeScene(dir, "b.yaml", "# b\nextends: a.yaml\n");
  r = runUampc("validate " + a);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(b + ":2:10: error: extends cycle: " + a + " -> " + b + " -> " + a), std::string::npos)
      << r.output;
  // A chain of 64 scenes is read; the 65th link is refused where it is written (a chain of 10,000
  // overflowed the stack).
  writeScene(dir, "link0.yaml", "name: chain\ncomponents:\n  motor: {type: motor_bridge}\n");
  for (int i = 1; i <= 64; ++i) {
    writeScene(dir, "link" + std::to_string(i) + ".yaml", "extends: link" + std::to_string(i - 1) + ".yaml\n");
  }
  EXPECT_EQ(runUampc("validate " + dir + "/link63.yaml").exit_code, 0);
  r = runUampc("validate " + dir + "/link64.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(dir + "/link1.yaml:1:10: error: extends: more than 64 scenes in one chain (from " + dir +
                          "/link64.yaml)"),
            std::string::npos)
      << r.output;
}

// What launch would refuse, validate refuses, and every message is readable: it names the value,
// what is wanted, and shows control bytes as \xNN instead of sending them to the terminal.
TEST(SceneValidation, MessagesAreReadableAndValidateCatchesWhatLaunchWouldRefuse) {
  const std::string dir = freshDirectory("validation_messages");
  const std::string scene = sourcePath("config/scenes/default.yaml");
  const std::pair<std::string, std::string> cases[] = {
      {scene + " --set seed=-7", "seed: cannot read '-7' as a whole number of 0 or more"},
      {scene + " --set 'world.map_offset=[1]'", "'map_offset' of component 'world' (map_provider) must be a list of 3 numbers, not 1"},
      {scene + " --set 'world.map_offset=[.nan,0,0]'", "must be a finite number, not .nan"},
      {scene + " --set world.world=file", "world: file needs map_file (component 'world', map_provider)"},
      {scene + " --set world.world=file", "world: file needs trajectory: file"},
      {scene + " --set world.trajectory=file", "trajectory: file needs trajectory_file"},
      {sourcePath("config/scenes"), "config/scenes: error: is a directory, not a file"},
      {writeScene(dir, "empty.yaml", "name: empty\ncomponents: {}\n"), "'components' is empty: the scene has nothing to run"},
      {writeScene(dir, "escape.yaml", "name: x\ncomponents:\n  \"\x1b[2Jbad\": {type: motor_bridge}\n"),
       "component name '\\x1b[2Jbad' must start with a letter"},
  };
  for (const auto& [args, wanted] : cases) {
    const CommandResult r = runUampc("validate " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(wanted), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << args;
  }
}

TEST(ComponentLoader, RefusesALibraryBuiltForAnotherAbiVersion) {
  const CommandResult r = runShell("UAMPC_COMPONENT_PATH=" + binaryPath("tests/bad_abi_components") + " " +
                                   binaryPath("bin/uampc") + " components");
  EXPECT_NE(r.exit_code, 0);
  // tests/components/bad_abi declares the runtime's version + 41.
  const std::string expected = "libuampc_bad_abi.so: built for component ABI version " +
                               std::to_string(kComponentAbiVersion + 41) + ", but this uampc runtime has version " +
                               std::to_string(kComponentAbiVersion) + "; rebuild";
  EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
}

// The element of a JSON array whose "name" (or "type") is name; null if none.
nlohmann::json named(const nlohmann::json& array, const std::string& key, const std::string& name) {
  for (const auto& element : array) {
    if (element.value(key, "") == name) return element;
  }
  return nullptr;
}

TEST(ComponentLoader, ListsInstalledComponentsWithPortsAndParametersAsJson) {
  const CommandResult r = runUampc("components --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json components = nlohmann::json::parse(r.output);
  const nlohmann::json motor = named(components, "type", "motor_bridge");
  ASSERT_FALSE(motor.is_null()) << r.output;
  const nlohmann::json state = named(motor["ports"], "name", "state");
  ASSERT_FALSE(state.is_null());
  EXPECT_EQ(state["direction"], "output");
  EXPECT_EQ(state["type"], "sensor_msgs/msg/JointState");
  EXPECT_EQ(state["topic"], "/motor/state");
  const nlohmann::json rate = named(motor["parameters"], "name", "encoder_rate");
  ASSERT_FALSE(rate.is_null());
  EXPECT_EQ(rate["type"], "double");
  EXPECT_EQ(rate["required"], false);
  EXPECT_EQ(rate["default"], 200.0);
  EXPECT_EQ(rate["min"], 1.0);
  EXPECT_EQ(rate["max"], 10000.0);
  // A required parameter has no default; a rig parameter says so.
  bool required_mode = false;
  for (const auto& c : components) {
    const nlohmann::json mode = named(c["parameters"], "name", "mode");
    if (!mode.is_null() && mode["required"] == true && !mode.contains("default")) required_mode = true;
  }
  EXPECT_TRUE(required_mode) << r.output;
  const nlohmann::json tilt = named(named(components, "type", "lo")["parameters"], "name", "tilt_deg");
  ASSERT_FALSE(tilt.is_null());
  EXPECT_EQ(tilt["rig"], true);
}

TEST(ComponentLoader, TextListingKeepsColumnsApartForLongNames) {
  const CommandResult r = runUampc("components");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The longest parameter name of the lo component once ran into its type column; now every
  // name is padded to the longest, and the types line up.
  EXPECT_NE(r.output.find("param  registration_weakest_points double"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("param  frame_velocity_std_angular  double"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("param  max_angular_acceleration    double"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("param  measurement_variance        double"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("output registered   sensor_msgs/msg/PointCloud2"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace uampc::test
