// A real 2 x 2 experiment (two scene entries x ua_mpc and zero, one seed, 3 s each, two at a
// time): results and report are written, and a second invocation runs nothing; a run whose done
// marker is gone is run again, and only that one.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>

#include "../e2e/command_runner.hpp"
#include "../e2e/test_domains.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> statuses(const std::string& results_json) {
  std::vector<std::string> out;
  for (const auto& run : YAML::LoadFile(results_json)["runs"]) out.push_back(run["status"].as<std::string>());
  return out;
}

TEST(ExperimentEndToEnd, RunsTheMatrixWritesTheReportAndResumes) {
  const std::string dir = freshDirectory("experiment_e2e_test");
  const std::string experiment = dir + "/experiment.yaml";
  std::ofstream(experiment) << "name: e2e\nduration: 3\nseeds: [1]\nscenes:\n"
                               "  - {name: campus, scene: " +
                                   sourcePath("config/scenes/campus_ua_mpc.yaml") +
                                   "}\n"
                                   "  - {name: campus_slow, scene: " +
                                   sourcePath("config/scenes/campus_ua_mpc.yaml") +
                                   ", overrides: [world.path_speed=0.75]}\n"
                                   "controllers:\n  - {name: ua_mpc, overrides: [controller.mode=ua_mpc]}\n"
                                   "  - {name: zero, overrides: [controller.mode=zero]}\n"
                                   "compare: {baseline: zero}\n";
  const std::string out = dir + "/out";
  const std::string command = "experiment " + experiment + " --out " + out + " --jobs 2 --domain-base " +
                              std::to_string(testDomain(DomainBlock::kExperimentE2e, 0));

  const CommandResult first = runUampc(command);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("4 runs (2 scenes x 2 controllers x 1 seeds)"), std::string::npos) << first.output;
  EXPECT_EQ(statuses(out + "/results.json"), (std::vector<std::string>(4, "ok")));
  const YAML::Node run = YAML::LoadFile(out + "/results.json")["runs"][0];
  EXPECT_GT(run["ate_m"].as<double>(), 0.0);
  EXPECT_GT(run["real_time_factor"].as<double>(), 0.0);
  EXPECT_GT(run["wall_time_s"].as<double>(), 0.0);
  EXPECT_DOUBLE_EQ(run["sim_time_s"].as<double>(), 3.0);
  const std::string md = readFile(out + "/results.md");
  EXPECT_NE(md.find("| controller | campus ATE m | campus CMPLT | campus_slow ATE m | campus_slow CMPLT |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| ua_mpc | "), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(out + "/report/index.html"));
  EXPECT_TRUE(fs::is_regular_file(out + "/report/campus_top_view.svg"));
  EXPECT_TRUE(fs::is_regular_file(out + "/runs/campus/zero/seed1/run.log"));
  // The clock's machine-readable progress, which the ETA reads: its last word is the run's end.
  const YAML::Node progress = YAML::LoadFile(out + "/runs/campus/zero/seed1/progress.json");
  EXPECT_TRUE(progress["finished"].as<bool>());
  EXPECT_DOUBLE_EQ(progress["sim_s"].as<double>(), 3.0);
  EXPECT_DOUBLE_EQ(progress["total_s"].as<double>(), 3.0);

  const auto log_time = fs::last_write_time(out + "/runs/campus/ua_mpc/seed1/run.log");
  const CommandResult second = runUampc(command);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("4/4 done (4 from before), 0 running"), std::string::npos) << second.output;
  EXPECT_EQ(statuses(out + "/results.json"), (std::vector<std::string>(4, "reused")));
  EXPECT_EQ(fs::last_write_time(out + "/runs/campus/ua_mpc/seed1/run.log"), log_time);

  fs::remove(out + "/runs/campus_slow/zero/seed1/done");  // as if it had been cut short
  const CommandResult third = runUampc(command);
  ASSERT_EQ(third.exit_code, 0) << third.output;
  EXPECT_NE(third.output.find("retrying runs/campus_slow/zero/seed1"), std::string::npos) << third.output;
  EXPECT_EQ(statuses(out + "/results.json"), (std::vector<std::string>{"reused", "reused", "reused", "ok"}));
}

TEST(ExperimentEndToEnd, AnInvalidOverrideStopsBeforeAnythingRuns) {
  const std::string dir = freshDirectory("experiment_e2e_invalid_test");
  std::ofstream(dir + "/experiment.yaml")
      << "scenes:\n  - {name: campus, scene: " + sourcePath("config/scenes/campus_ua_mpc.yaml") +
             "}\n"
             "controllers:\n  - {name: typo, overrides: [controller.mdoe=zero]}\n";
  const CommandResult r = runUampc("experiment " + dir + "/experiment.yaml --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("controller 'typo'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mdoe"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out/runs"));
}

TEST(ExperimentEndToEnd, HelpPrintsTheUsageAndRunsNothing) {
  const CommandResult r = runUampc("experiment --help");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("usage: uampc experiment EXPERIMENT.yaml --out DIR"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace uampc::test
