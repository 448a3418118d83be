// A real 2 x 2 experiment (two scene entries x ua_mpc and zero, one seed, 3 s each, two at a
// time): results and report are written, and a second invocation runs nothing; a run whose done
// marker is gone is run again, and only that one. An output directory that cannot be written is
// named with the reason, without an abort.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "../e2e/command_runner.hpp"
#include "../e2e/full_disk.hpp"
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

// One short run of a test scene (the evaluator with a test publisher, 2 s), one at a time.
std::string smallExperiment(const std::string& dir, const std::string& seeds = "[1]") {
  std::ofstream(dir + "/experiment.yaml") << "name: small\nseeds: " + seeds + "\nscenes:\n  - {name: panorama, scene: " +
                                                 sourcePath("tests/scenes/evaluator_bad_panorama.yaml") +
                                                 "}\ncontrollers:\n  - {name: none, overrides: []}\n";
  return "experiment " + dir + "/experiment.yaml --jobs 1 --domain-base " +
         std::to_string(testDomain(DomainBlock::kExperimentE2e, 2));
}

// --out that cannot be made, as `uampc launch --out` reports it (docs/user/faults.md): the path
// and the system's reason, exit code 1, nothing run. As root, a read-only directory cannot be
// made by chmod; a path under a regular file is refused the same way, with "Not a directory".
// Before, both aborted (exit code 134, "terminate called after throwing ...").
TEST(ExperimentEndToEnd, AnOutputDirectoryThatCannotBeMadeIsNamedWithTheReason) {
  const std::string dir = freshDirectory("experiment_e2e_out_unwritable");
  const std::string command = smallExperiment(dir);
  std::ofstream(dir + "/a_file") << "not a directory";
  const CommandResult under_a_file = runUampc(command + " --out " + dir + "/a_file/out");
  EXPECT_EQ(under_a_file.exit_code, 1) << under_a_file.output;
  EXPECT_NE(under_a_file.output.find("cannot create the output directory " + dir + "/a_file/out: Not a directory"),
            std::string::npos)
      << under_a_file.output;
  const std::string long_name = dir + "/" + std::string(300, 'n');
  const CommandResult too_long = runUampc(command + " --out " + long_name);
  EXPECT_EQ(too_long.exit_code, 1) << too_long.output;
  EXPECT_NE(too_long.output.find(long_name + ": File name too long; nothing was run"), std::string::npos)
      << too_long.output;
}

// A full disk (full_disk.hpp: every file limited in size, EFBIG where a disk gives ENOSPC). At
// 512 bytes the plan itself cannot be written: named, exit code 1, no file left. With a limit
// between the plan's size and the results' (both name the checkout's paths, so the limit is taken
// from an unlimited run; each seed adds more to the results than to the plan, and four put a
// 512-byte step between them for any checkout path of under about 300 characters) the plan
// is written and the runs start, but the evaluator cannot write metrics.json (the run fails, and
// its failed marker is written) and the experiment cannot write results.json: named, exit code 1,
// and neither file is left half-written. Before, the experiment aborted at the first of them.
TEST(ExperimentEndToEnd, AFullDiskIsNamedWithTheFileAndLeavesNothingHalfWritten) {
  const std::string dir = freshDirectory("experiment_e2e_full_disk");
  const std::string out = dir + "/out";
  const std::string command = "UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " +
                              binaryPath("bin/uampc") + " " + smallExperiment(dir, "[1, 2, 3, 4]") + " --out " + out;
  // The sizes a disk with room gives: a limit (in dash's 512-byte steps) the plan fits under and
  // the results do not.
  const CommandResult unlimited = runShell(command);
  ASSERT_EQ(unlimited.exit_code, 0) << unlimited.output;  // the runs fail; the experiment reports them
  const std::uintmax_t plan_bytes = fs::file_size(out + "/experiment.json");
  const std::uintmax_t results_bytes = fs::file_size(out + "/results.json");
  const std::size_t plan_fits = (results_bytes - 1) / 512 * 512;
  ASSERT_GT(plan_bytes, 512u);
  ASSERT_GE(plan_fits, plan_bytes) << "results.json " << results_bytes << " bytes, experiment.json " << plan_bytes;
  fs::remove_all(out);

  const CommandResult no_plan = runShell(withFileSizeLimit(512, command));
  EXPECT_EQ(no_plan.exit_code, 1) << no_plan.output;
  EXPECT_NE(no_plan.output.find("uampc experiment: cannot write " + out + "/experiment.json: File too large"),
            std::string::npos)
      << no_plan.output;
  EXPECT_FALSE(fs::exists(out + "/experiment.json"));
  EXPECT_FALSE(fs::exists(out + "/experiment.json.partial"));

  const CommandResult no_results = runShell(withFileSizeLimit(plan_fits, command));
  EXPECT_EQ(no_results.exit_code, 1) << no_results.output;
  EXPECT_NE(no_results.output.find("runs/panorama/none/seed1 failed (exit code 1)"), std::string::npos)
      << no_results.output;
  EXPECT_NE(no_results.output.find("uampc experiment: cannot write " + out + "/results.json: File too large"),
            std::string::npos)
      << no_results.output;
  const std::string run = out + "/runs/panorama/none/seed1";
  EXPECT_FALSE(fs::exists(run + "/metrics.json"));
  EXPECT_FALSE(fs::exists(run + "/done"));
  EXPECT_EQ(readFile(run + "/failed"), "exit code 1\n");
  EXPECT_FALSE(fs::exists(out + "/results.json"));
  for (const std::string& d : {out, run}) {
    for (const auto& entry : fs::directory_iterator(d)) EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  }
}

}  // namespace
}  // namespace uampc::test
