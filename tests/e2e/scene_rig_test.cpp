// The rig once (docs/user/scenes.md, "The rig"): the LiDAR's model, tilt and offset are written
// once in a scene's rig: block (or --set rig.NAME=VALUE) and reach every installed component that
// declares them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "command_runner.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc::test {
namespace {

ComponentCatalog installedComponents() { return ComponentCatalog({binaryPath("lib/uampc/components")}); }

// The value of one parameter in every component that declares it, by instance name.
std::map<std::string, ParameterValue> valuesOf(const Scene& scene, const std::string& parameter) {
  std::map<std::string, ParameterValue> values;
  for (const auto& c : scene.components) {
    if (auto it = c.params.find(parameter); it != c.params.end()) values[c.name] = it->second;
  }
  return values;
}

TEST(SceneRig, ASetRigTiltReachesEveryComponentThatUsesTheRig) {
  ComponentCatalog catalog = installedComponents();
  const Scene scene = loadScene(sourcePath("config/scenes/default.yaml"), {parseOverride("rig.tilt_deg=45")}, catalog);
  const auto tilts = valuesOf(scene, "tilt_deg");
  // raycaster, lo, mpc, evaluator and tf_broadcaster describe the same rig.
  EXPECT_EQ(tilts.size(), 5u);
  EXPECT_TRUE(tilts.count("tf"));
  for (const auto& [instance, value] : tilts) EXPECT_EQ(std::get<double>(value), 45.0) << instance;
  EXPECT_EQ(std::get<double>(scene.rig.at("tilt_deg")), 45.0);
}

TEST(SceneRig, TheLidarModelReachesTheSimulatorAndTheController) {
  ComponentCatalog catalog = installedComponents();
  const Scene scene =
      loadScene(sourcePath("config/scenes/default.yaml"), {parseOverride("rig.lidar_model=velodyne_vlp16")}, catalog);
  const auto models = valuesOf(scene, "lidar_model");
  ASSERT_EQ(models.size(), 2u);
  for (const auto& [instance, value] : models) EXPECT_EQ(std::get<std::string>(value), "velodyne_vlp16") << instance;
}

TEST(SceneRig, ARigParameterInOneComponentIsRefusedWithWhereToPutIt) {
  const CommandResult r = runUampc("validate " + sourcePath("config/scenes/default.yaml") + " --set lidar.tilt_deg=45");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("'tilt_deg' is part of the rig"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--set rig.tilt_deg="), std::string::npos) << r.output;
}

TEST(SceneRig, RigValuesAreValidatedLikeParameters) {
  const std::string scene = sourcePath("config/scenes/default.yaml");
  CommandResult r = runUampc("validate " + scene + " --set rig.tilt_deg=400");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("parameter 'tilt_deg' of the rig is 400, out of bounds [-180, 180]"), std::string::npos)
      << r.output;
  r = runUampc("validate " + scene + " --set rig.tilt_dg=10");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("uses rig parameter 'tilt_dg'; did you mean 'tilt_deg'?"), std::string::npos) << r.output;
}

// The full rotation and the tilt say one thing two ways: both given is an error at file:line, one
// alone is taken, and a rotation of three angles only.
TEST(SceneRig, ARotationAndATiltTogetherAreRefusedWithWhereTheyAre) {
  const std::string dir = freshDirectory("scene_rig_rotation");
  const std::string scene = dir + "/both.yaml";
  std::ofstream(scene) << "extends: " << sourcePath("config/scenes/default.yaml") << "\n"
                       << "rig:\n  tilt_deg: 30\n  lidar_rotation_rpy_deg: [30, 0, 1]\n";
  CommandResult r = runUampc("validate " + scene);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(scene + ":4:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rig.lidar_rotation_rpy_deg and rig.tilt_deg are both given"), std::string::npos) << r.output;

  // The default scene without its tilt_deg line takes a rotation from --set.
  std::ifstream default_scene(sourcePath("config/scenes/default.yaml"));
  std::ofstream untilted(dir + "/untilted.yaml");
  for (std::string line; std::getline(default_scene, line);)
    if (line.find("tilt_deg:") == std::string::npos) untilted << line << "\n";
  untilted.close();
  ComponentCatalog catalog = installedComponents();
  const Scene rotated = loadScene(dir + "/untilted.yaml",
                                  {parseOverride("rig.lidar_rotation_rpy_deg=[30, 0.5, -1]"),
                                   parseOverride("rig.encoder_offset_deg=2"), parseOverride("rig.time_offset=0.003")},
                                  catalog);
  const auto rotations = valuesOf(rotated, "lidar_rotation_rpy_deg");
  EXPECT_EQ(rotations.size(), 5u);
  for (const auto& [instance, value] : rotations)
    EXPECT_EQ(std::get<std::vector<double>>(value), (std::vector<double>{30, 0.5, -1})) << instance;
  EXPECT_EQ(valuesOf(rotated, "encoder_offset_deg").size(), 5u);
  EXPECT_EQ(valuesOf(rotated, "time_offset").size(), 5u);

  r = runUampc("validate " + sourcePath("config/scenes/default.yaml") + " --set 'rig.lidar_rotation_rpy_deg=[30, 0]'");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("must be a list of 3 numbers, not 2"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace uampc::test
