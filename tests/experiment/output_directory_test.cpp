// Whose --out it is (docs/decisions/experiment-output-lock.md): one experiment at a time on an
// output directory, its lock file a regular file of its own; and no attempt of a run (an
// experiment's, a --run-task's) clears a run another attempt holds.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "../e2e/background_launch.hpp"
#include "../e2e/command_runner.hpp"
#include "../e2e/test_domains.hpp"
#include "motor_experiment.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;

std::string hostName() {
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return name;
}

// The reported case: a second experiment on the --out of a running one deleted the first's run
// directory in flight and ran it again. Now it is refused, naming the first (pid and host), and
// so is a --run-task of the run the first is running (a Slurm task does not take the --out lock,
// but no attempt clears a run another attempt holds); the first goes on untouched.
TEST(OutputDirectory, ASecondExperimentAndARunTaskLeaveTheRunningExperimentAlone) {
  const MotorExperiment first = motorExperiment(freshDirectory("out_lock_two_experiments"), 30, true, 6);
  const pid_t running = startUampc(first.command(), first.out + ".log");
  ASSERT_TRUE(waitFor([&] { return runIsStepping(first); }, std::chrono::seconds(60))) << readFile(first.out + ".log");
  const pid_t launcher = launcherOnDomain(first.domain);
  ASSERT_GT(launcher, 0);
  const std::string holder = "pid " + std::to_string(running) + " on " + hostName();

  MotorExperiment second = first;
  second.domain = testDomain(DomainBlock::kExperimentE2e, 7);
  const CommandResult refused = runUampc(second.command());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find(first.out + " is in use by another experiment"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find(holder), std::string::npos) << refused.output;

  const CommandResult task =
      runUampc("experiment --run-task 0 --out " + first.out + " --domain-base " + std::to_string(second.domain));
  EXPECT_EQ(task.exit_code, 4) << task.output;
  EXPECT_NE(task.output.find("runs/motor/constant/seed1 is being run by " + holder), std::string::npos) << task.output;

  EXPECT_EQ(launcherOnDomain(second.domain), -1);  // nothing started the run again
  EXPECT_EQ(launcherOnDomain(first.domain), launcher);
  EXPECT_TRUE(fs::exists(first.run + "/run_info.json"));  // its directory was not emptied
  ASSERT_EQ(kill(-running, SIGINT), 0);
  EXPECT_EQ(exitCodeOf(running), 130) << readFile(first.out + ".log");
  EXPECT_FALSE(fs::exists(first.run + "/done"));
}

// What a --no-wait Slurm submission leaves: tasks running with no command holding --out. An
// experiment started then on the directory runs what it can and leaves the task's run alone,
// naming the task; the task goes on.
TEST(OutputDirectory, AnExperimentLeavesARunATaskIsRunningAlone) {
  const MotorExperiment e = motorExperiment(freshDirectory("out_lock_task_running"), 30, true, 11);
  const CommandResult planned = runUampc("experiment " + e.file + " --out " + e.out + " --plan-only");
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  const pid_t task = startUampc("experiment --run-task 0 --out " + e.out + " --domain-base " + std::to_string(e.domain),
                                e.out + "/task.log");
  ASSERT_TRUE(waitFor([&] { return runIsStepping(e); }, std::chrono::seconds(60))) << readFile(e.out + "/task.log");
  const pid_t launcher = launcherOnDomain(e.domain);
  ASSERT_GT(launcher, 0);

  MotorExperiment local = e;
  local.domain = testDomain(DomainBlock::kExperimentE2e, 7);
  const CommandResult experiment = runUampc(local.command());
  EXPECT_EQ(experiment.exit_code, 1) << experiment.output;  // its one run is not done
  EXPECT_NE(experiment.output.find("runs/motor/constant/seed1 left alone: it is being run by pid " +
                                   std::to_string(task) + " on " + hostName()),
            std::string::npos)
      << experiment.output;
  EXPECT_EQ(launcherOnDomain(local.domain), -1);
  EXPECT_EQ(launcherOnDomain(e.domain), launcher);
  EXPECT_TRUE(fs::exists(e.run + "/run_info.json"));
  ASSERT_EQ(kill(-task, SIGINT), 0);
  EXPECT_EQ(exitCodeOf(task), 130) << readFile(e.out + "/task.log");
}

// The lock file is opened without following a symbolic link, and must be a regular file: an
// experiment.lock planted as a link to another file (which the lock would truncate) or made a
// directory is refused by name, and the file it points to is left as it was.
TEST(OutputDirectory, ALockFileThatIsNotARegularFileOfItsOwnIsRefused) {
  const std::string dir = freshDirectory("out_lock_not_regular");
  const MotorExperiment e = motorExperiment(dir, 2, false, 8);
  fs::create_directories(e.out);
  std::ofstream(dir + "/precious.txt") << "keep me\n";
  fs::create_symlink(dir + "/precious.txt", e.out + "/experiment.lock");
  const CommandResult link = runUampc(e.command());
  EXPECT_EQ(link.exit_code, 2) << link.output;
  EXPECT_NE(link.output.find(e.out + "/experiment.lock"), std::string::npos) << link.output;
  EXPECT_NE(link.output.find("symbolic link"), std::string::npos) << link.output;
  EXPECT_EQ(readFile(dir + "/precious.txt"), "keep me\n");
  EXPECT_FALSE(fs::exists(e.out + "/runs"));

  fs::remove(e.out + "/experiment.lock");
  fs::create_directory(e.out + "/experiment.lock");
  const CommandResult directory = runUampc(e.command());
  EXPECT_EQ(directory.exit_code, 2) << directory.output;
  EXPECT_NE(directory.output.find(e.out + "/experiment.lock"), std::string::npos) << directory.output;
  EXPECT_FALSE(fs::exists(e.out + "/runs"));
}

}  // namespace
}  // namespace uampc::test
