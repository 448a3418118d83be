// The experiment file: a good file reads as written; every kind of mistake is reported with
// file:line:column before anything runs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "command_runner.hpp"
#include "experiment/experiment_file.hpp"
#include "report/test/fake_runs.hpp"

namespace uampc::app {
namespace {

class ExperimentFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::freshDirectory("experiment_file_test");
    test::writeText(dir_ + "/scenes/campus.yaml", "components: {}\n");
  }
  // Writes an experiment file and returns its path.
  std::string write(const std::string& text) {
    const std::string path = dir_ + "/experiment.yaml";
    test::writeText(path, text);
    return path;
  }
  // The messages of loading `text`, expected to fail.
  std::vector<std::string> errors(const std::string& text, const std::map<std::string, std::string>& variables = {}) {
    try {
      loadExperiment(write(text), variables);
    } catch (const ExperimentError& e) {
      return e.messages();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return {};
  }
  std::string at(int line, int column) const {
    return dir_ + "/experiment.yaml:" + std::to_string(line) + ":" + std::to_string(column) + ": error: ";
  }
  std::string dir_;
};

MATCHER_P(StartsWith, prefix, "") { return arg.rfind(prefix, 0) == 0; }

TEST_F(ExperimentFileTest, GoodFileReadsAsWritten) {
  const Experiment e = loadExperiment(write("name: paper\n"
                                            "duration: 12.5\n"
                                            "seeds: [3, 1]\n"
                                            "scenes:\n"
                                            "  - name: campus\n"
                                            "    scene: scenes/campus.yaml\n"
                                            "    overrides: [\"world.trajectory_file=${data_dir}/ntu.csv\"]\n"
                                            "controllers:\n"
                                            "  - name: ua_mpc\n"
                                            "    overrides: [controller.mode=ua_mpc]\n"
                                            "  - name: fast\n"
                                            "compare: {subject: fast, baseline: ua_mpc}\n"),
                                      {{"data_dir", "/data"}});
  EXPECT_EQ(e.name, "paper");
  ASSERT_TRUE(e.duration_s);
  EXPECT_DOUBLE_EQ(*e.duration_s, 12.5);
  EXPECT_EQ(e.seeds, (std::vector<std::uint64_t>{3, 1}));
  ASSERT_EQ(e.scenes.size(), 1u);
  EXPECT_EQ(e.scenes[0].scene_file, dir_ + "/scenes/campus.yaml");
  EXPECT_EQ(e.scenes[0].overrides, (std::vector<std::string>{"world.trajectory_file=/data/ntu.csv"}));
  ASSERT_EQ(e.controllers.size(), 2u);
  EXPECT_EQ(e.controllers[1].name, "fast");
  EXPECT_TRUE(e.controllers[1].overrides.empty());
  EXPECT_EQ(e.subject, "fast");
  EXPECT_EQ(e.baseline, "ua_mpc");
}

TEST_F(ExperimentFileTest, DefaultsAreThePapersControllersAndOneSeed) {
  const Experiment e = loadExperiment(write("scenes: [{name: campus, scene: scenes/campus.yaml}]\n"), {});
  EXPECT_EQ(e.name, "experiment");
  EXPECT_FALSE(e.duration_s);
  EXPECT_EQ(e.seeds, (std::vector<std::uint64_t>{1}));
  std::vector<std::string> names;
  for (const auto& c : e.controllers) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"ua_mpc", "constant_1.8", "constant_3.6", "constant_7.2", "zero"}));
  EXPECT_EQ(e.subject, "ua_mpc");
  EXPECT_EQ(e.baseline, "constant_3.6");
}

TEST_F(ExperimentFileTest, UnknownKeys) {
  EXPECT_THAT(errors("scenes: [{name: campus, scene: scenes/campus.yaml}]\nseed: [1]\n"),
              ::testing::ElementsAre(StartsWith(at(2, 1) + "unknown key 'seed' in the experiment")));
  EXPECT_THAT(errors("scenes:\n  - name: campus\n    scene: scenes/campus.yaml\n    overide: [a.b=1]\n"),
              ::testing::ElementsAre(at(4, 5) + "unknown key 'overide' in a scene entry; did you mean 'overrides'?"));
  // Nothing close: the keys it could have been (the scene files' collector, runtime/yaml_errors.hpp).
  EXPECT_THAT(errors("scenes:\n  - name: campus\n    scene: scenes/campus.yaml\n    weather: rain\n"),
              ::testing::ElementsAre(at(4, 5) + "unknown key 'weather' in a scene entry (allowed: name, overrides, "
                                                "scene)"));
}

TEST_F(ExperimentFileTest, MissingSceneFile) {
  EXPECT_THAT(errors("scenes:\n  - name: campus\n    scene: scenes/nowhere.yaml\n"),
              ::testing::ElementsAre(at(3, 12) + "scene file not found: " + dir_ + "/scenes/nowhere.yaml"));
}

TEST_F(ExperimentFileTest, BadTypes) {
  const auto e = errors(
      "duration: soon\nseeds: [1, two, -3]\nscenes: {name: campus}\n"
      "controllers:\n  - name: [a, b]\n");
  EXPECT_THAT(e, ::testing::ElementsAre(StartsWith(at(1, 11) + "duration must be a number"),
                                        StartsWith(at(2, 12) + "a seed must be a non-negative integer, not 'two'"),
                                        StartsWith(at(2, 17) + "a seed must be a non-negative integer, not '-3'"),
                                        StartsWith(at(3, 9) + "scenes must be a non-empty list"),
                                        StartsWith(at(5, 11) + "controller name must be a single value")));
}

TEST_F(ExperimentFileTest, BadOverrides) {
  const auto e = errors(
      "scenes:\n  - name: campus\n    scene: scenes/campus.yaml\n"
      "    overrides: [novalue, seed=3, \"x=${data_dir}\", \"y=${nope}\"]\n");
  EXPECT_THAT(e, ::testing::ElementsAre(StartsWith(at(4, 17) + "'novalue' is not NAME=VALUE"),
                                        StartsWith(at(4, 26) + "seed is set by the experiment"),
                                        StartsWith(at(4, 34) + "${data_dir} is used but no --data-dir was given"),
                                        StartsWith(at(4, 51) + "unknown variable ${nope}")));
}

TEST_F(ExperimentFileTest, NamesMustBeUniqueAndSafeForDirectories) {
  const auto e = errors(
      "scenes:\n  - {name: a/b, scene: scenes/campus.yaml}\n"
      "controllers:\n  - {name: x}\n  - {name: x}\ncompare: {baseline: y}\n");
  EXPECT_THAT(e, ::testing::ElementsAre(StartsWith(at(2, 12) + "scene name 'a/b' may only hold"),
                                        StartsWith(at(5, 12) + "controller name 'x' appears twice"),
                                        StartsWith(at(6, 21) + "compare.baseline: no controller named 'y'")));
}

// A name of 300 characters was valid in --dry-run and aborted the run (the directory name was too
// long); keys written twice or that are not names are refused as in scenes (docs/user/faults.md).
TEST_F(ExperimentFileTest, NamesAreBoundedAndKeysAreNamesWrittenOnce) {
  const std::string long_name(300, 'n');
  const auto e =
      errors("scenes:\n  - {name: " + long_name + ", scene: scenes/campus.yaml}\ncontrollers:\n  - {name: x}\n");
  EXPECT_THAT(
      e, ::testing::ElementsAre(StartsWith(at(2, 12) + "scene name 'nnnnnnnnnnnnnnnnnnnn...' is longer than 100")));
  const auto twice = errors("scenes:\n  - {name: a, scene: scenes/campus.yaml}\nscenes: []\n");
  EXPECT_THAT(twice, ::testing::ElementsAre(StartsWith(at(3, 1) + "key 'scenes' is written twice")));
  const auto listed = errors("? [a]\n: 1\n");
  EXPECT_THAT(listed, ::testing::ElementsAre(StartsWith(at(1, 3) + "a key must be a plain name")));
}

TEST_F(ExperimentFileTest, YamlSyntaxAndMissingScenes) {
  EXPECT_THAT(errors("scenes: [unclosed\n"),
              ::testing::ElementsAre(StartsWith(dir_ + "/experiment.yaml:2:1: error: ")));
  EXPECT_THAT(errors("seeds: [1]\n"), ::testing::ElementsAre(at(1, 1) + "the experiment has no 'scenes'"));
}

}  // namespace
}  // namespace uampc::app
