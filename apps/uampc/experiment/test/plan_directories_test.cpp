// A plan's run directories lie inside DIR/runs (docs/decisions/experiment-plan-inside-out.md):
// lexically, and where the path exists, through its symbolic links; no two share a directory or
// hold one another.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "command_runner.hpp"
#include "experiment/plan_directories.hpp"
#include "experiment/run_attempt.hpp"

namespace uampc::app {
namespace {

namespace fs = std::filesystem;

std::string problemOf(const std::string& out, const std::string& directory) {
  return runDirectoryProblem(out, 0, directory);
}

TEST(PlanDirectories, ADirectoryUnderRunsIsInside) {
  const std::string out = test::freshDirectory("plan_directories_inside") + "/out";
  EXPECT_EQ(problemOf(out, "runs/campus/ua_mpc/seed1"), "");
  EXPECT_EQ(problemOf(out + "/", "runs/campus/ua_mpc/seed1/"), "");
  EXPECT_EQ(problemOf(out, "runs/a/../b"), "");  // normalised: runs/b
}

TEST(PlanDirectories, DirectoriesOutsideRunsAreRefusedNamingWhereTheyLead) {
  const std::string dir = test::freshDirectory("plan_directories_outside");
  const std::string out = dir + "/out";
  EXPECT_EQ(problemOf(out, "../precious_dir"),
            "plan entry 0 (../precious_dir): " + dir + "/precious_dir is not inside " + out + "/runs");
  EXPECT_EQ(problemOf(out, "runs/../../x"),
            "plan entry 0 (runs/../../x): " + dir + "/x is not inside " + out + "/runs");
  EXPECT_EQ(problemOf(out, "/etc"), "plan entry 0 (/etc): an absolute path; a run's directory is relative to " + out);
  EXPECT_NE(problemOf(out, "runs"), "");  // the runs' own directory: emptying it empties them all
  EXPECT_NE(problemOf(out, "runs/."), "");
  EXPECT_NE(problemOf(out, "slurm"), "");  // inside --out, but the experiment's own files
  EXPECT_NE(problemOf(out, "experiment.json"), "");
  EXPECT_NE(problemOf(out, ""), "");
}

TEST(PlanDirectories, ASymbolicLinkOutOfTheOutputDirectoryIsFollowed) {
  const std::string dir = test::freshDirectory("plan_directories_link");
  const std::string out = dir + "/out";
  fs::create_directories(out + "/runs");
  fs::create_directories(dir + "/elsewhere");
  fs::create_directory_symlink(dir + "/elsewhere", out + "/runs/link");
  EXPECT_EQ(problemOf(out, "runs/link/seed1"),
            "plan entry 0 (runs/link/seed1): " + out + "/runs/link/seed1 leads to " + dir +
                "/elsewhere/seed1 (through a symbolic link), which is not inside " + out + "/runs");
  // A link that stays inside is fine; so is --out itself reached through a link.
  fs::create_directory_symlink(out + "/runs", out + "/runs/here");
  EXPECT_EQ(problemOf(out, "runs/here/seed1"), "");
  fs::create_directory_symlink(out, dir + "/out_link");
  EXPECT_EQ(problemOf(dir + "/out_link", "runs/a/seed1"), "");
}

PlannedRun runIn(const std::string& directory) {
  PlannedRun run;
  run.directory = directory;
  return run;
}

TEST(PlanDirectories, NoTwoEntriesShareADirectoryOrHoldOneAnother) {
  const std::string out = test::freshDirectory("plan_directories_plan") + "/out";
  EXPECT_EQ(planDirectoriesProblem(out, {runIn("runs/a/seed1"), runIn("runs/a-b/seed1"), runIn("runs/a/seed2")}), "");
  EXPECT_EQ(planDirectoriesProblem(out, {runIn("runs/a/seed1"), runIn("runs/b"), runIn("runs/a/seed1/")}),
            "plan entry 0 (runs/a/seed1) and plan entry 2 (runs/a/seed1/): one run's directory would hold the other's");
  EXPECT_EQ(planDirectoriesProblem(out, {runIn("runs/a/seed1/x"), runIn("runs/a-c"), runIn("runs/a/seed1")}),
            "plan entry 2 (runs/a/seed1) and plan entry 0 (runs/a/seed1/x): one run's directory would hold the "
            "other's");
  EXPECT_EQ(planDirectoriesProblem(out, {runIn("runs/a/seed1"), runIn("../x")}),
            "plan entry 1 (../x): " + fs::path(out).parent_path().string() + "/x is not inside " + out + "/runs");
}

// An attempt checks again right before it empties the directory, and touches nothing outside.
TEST(RunAttempt, ADirectoryOutsideIsNotTouched) {
  const std::string dir = test::freshDirectory("run_attempt_outside");
  fs::create_directories(dir + "/precious_dir");
  std::ofstream(dir + "/precious_dir/keep.txt") << "keep me\n";
  const AttemptStart start = beginAttempt(dir + "/out", 4, runIn("../precious_dir"), "pid 1 on here");
  EXPECT_FALSE(start.lock);
  EXPECT_EQ(start.error, "plan entry 4 (../precious_dir): " + dir + "/precious_dir is not inside " + dir + "/out/runs");
  EXPECT_EQ(test::readFile(dir + "/precious_dir/keep.txt"), "keep me\n");
  EXPECT_FALSE(fs::exists(dir + "/precious_dir/" + kAttemptLockFile));
}

}  // namespace
}  // namespace uampc::app
