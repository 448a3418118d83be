// A plan's run directories lie inside --out/runs, or the plan is refused before anything is
// removed or written (docs/decisions/experiment-plan-inside-out.md): by --run-task and --collect,
// which read DIR/experiment.json, and by the experiment that plans.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../e2e/command_runner.hpp"
#include "motor_experiment.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

void setPlannedDirectory(const std::string& out, const std::string& directory) {
  const std::string path = out + "/experiment.json";
  nlohmann::json plan = nlohmann::json::parse(readFile(path));
  plan["plan"][0]["directory"] = directory;
  std::ofstream(path) << plan.dump(2);
}

// The reported case: a plan entry's directory "../precious_dir" made `--run-task` remove the
// file in it, and an absolute path escaped too. Every such plan is refused, by --run-task and by
// --collect, naming the entry and where its path leads, and nothing is removed; a directory
// reached through a symbolic link out of --out is refused the same way.
TEST(PlanInsideOut, APlanWhoseRunDirectoryLiesOutsideTheOutputDirectoryIsRefused) {
  const std::string dir = freshDirectory("out_plan_escapes");
  const MotorExperiment e = motorExperiment(dir, 2, false, 9);
  const CommandResult planned = runUampc("experiment " + e.file + " --out " + e.out + " --plan-only");
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  fs::create_directories(dir + "/precious_dir");
  std::ofstream(dir + "/precious_dir/keep.txt") << "keep me\n";
  fs::create_directories(e.out + "/runs");
  fs::create_directory_symlink(dir + "/precious_dir", e.out + "/runs/link");

  const std::string task = "experiment --run-task 0 --out " + e.out + " --domain-base " + std::to_string(e.domain);
  for (const std::string& escaping :
       {std::string("../precious_dir"), dir + "/precious_dir", std::string("runs/link/keep.txt")}) {
    SCOPED_TRACE(escaping);
    setPlannedDirectory(e.out, escaping);
    const CommandResult refused = runUampc(task);
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find("plan entry 0 (" + escaping + ")"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find(dir + "/precious_dir"), std::string::npos) << refused.output;
    const CommandResult collect = runUampc("experiment --collect " + e.out);
    EXPECT_EQ(collect.exit_code, 2) << collect.output;
    EXPECT_EQ(readFile(dir + "/precious_dir/keep.txt"), "keep me\n");
  }
}

// The local runner's plan goes through the same check: runs/ made a link to another directory
// would have the experiment write (and on a retry, remove) there.
TEST(PlanInsideOut, AnExperimentWhoseRunsDirectoryLeadsOutOfTheOutputDirectoryIsRefused) {
  const std::string dir = freshDirectory("out_runs_link");
  const MotorExperiment e = motorExperiment(dir, 2, false, 10);
  fs::create_directories(dir + "/elsewhere");
  fs::create_directories(e.out);
  fs::create_directory_symlink(dir + "/elsewhere", e.out + "/runs");
  const CommandResult refused = runUampc(e.command());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("plan entry 0 (runs/motor/constant/seed1)"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find(dir + "/elsewhere/motor/constant/seed1"), std::string::npos) << refused.output;
  EXPECT_TRUE(fs::is_empty(dir + "/elsewhere"));
}

}  // namespace
}  // namespace uampc::test
