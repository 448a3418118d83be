// Every invalid scene in tests/scenes/invalid/ is refused before anything starts, with a non-zero
// exit and the message its first line announces ("# expect: LINE:COLUMN: error: text"), prefixed
// by the scene's path.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "command_runner.hpp"

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
    const CommandResult r = runUampc("validate " + entry.path().string());
    EXPECT_EQ(r.exit_code, 0) << entry.path() << "\n" << r.output;
  }
}

TEST(ComponentLoader, RefusesALibraryBuiltForAnotherAbiVersion) {
  const CommandResult r = runShell("UAMPC_COMPONENT_PATH=" + binaryPath("tests/bad_abi_components") + " " +
                                   binaryPath("bin/uampc") + " components");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("libuampc_bad_abi.so: built for component ABI version 42, but this uampc runtime has "
                          "version 1; rebuild"),
            std::string::npos)
      << r.output;
}

TEST(ComponentLoader, ListsInstalledComponentsWithPortsAndParametersAsJson) {
  const CommandResult r = runUampc("components --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"type\": \"motor_bridge\""), std::string::npos);
  EXPECT_NE(r.output.find("{\"name\": \"state\", \"direction\": \"output\", \"type\": \"sensor_msgs/msg/JointState\", "
                          "\"topic\": \"/motor/state\""),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("{\"name\": \"encoder_rate\", \"type\": \"double\", \"required\": false, \"default\": 200, "
                          "\"min\": 1, \"max\": 10000"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("{\"name\": \"mode\", \"type\": \"string\", \"required\": true"), std::string::npos);
}

TEST(ComponentLoader, TextListingKeepsColumnsApartForLongNames) {
  const CommandResult r = runUampc("components");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The longest parameter name of the lo component once ran into its type column; now every
  // name is padded to the longest, and the types line up.
  EXPECT_NE(r.output.find("param  max_angular_acceleration double"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("param  measurement_variance     double"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("output registered   sensor_msgs/msg/PointCloud2"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace uampc::test
