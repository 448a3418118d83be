// What the launcher does when a component or process misbehaves, and on Ctrl-C, SIGTERM and SIGHUP.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/metrics_file.hpp"

namespace uampc::test {
namespace {

CommandResult runFault(const std::string& mode, int domain, const std::string& more = "") {
  return runUampc("launch " + sourcePath("tests/scenes/fault.yaml") + " --set fault.mode=" + mode +
                  " --set domain_id=" + std::to_string(domain) + more);
}

TEST(Supervision, AThrowingComponentStopsTheRunWithItsNameAndTime) {
  const CommandResult r = runFault("throw", testDomain(DomainBlock::kSupervision, 0));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("component 'fault' failed in a timer at t=0.1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("injected failure"), std::string::npos) << r.output;
}

TEST(Supervision, ACrashedProcessIsReportedWithNameAndSignal) {
  const CommandResult r = runFault("abort", testDomain(DomainBlock::kSupervision, 1));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("process 'faulty'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("killed by signal 6 (Aborted)"), std::string::npos) << r.output;
}

TEST(Supervision, AHungComponentTimesOutInsteadOfHangingTheRun) {
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = runFault("hang", testDomain(DomainBlock::kSupervision, 2));
  EXPECT_EQ(r.exit_code, 1);
  // The processes step themselves (clock.in_process): the one that waits names the one it waits for.
  EXPECT_NE(r.output.find("run failed: process 'main': acknowledgements of step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("from process(es) faulty did not arrive"), std::string::npos) << r.output;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  // The launcher's clock names the process that did not acknowledge its tick.
  const CommandResult ticked =
      runFault("hang", testDomain(DomainBlock::kSupervision, 5), " --set clock.in_process=false");
  EXPECT_EQ(ticked.exit_code, 1);
  EXPECT_NE(ticked.output.find("no acknowledgement of the step from process(es) faulty"), std::string::npos)
      << ticked.output;
}

TEST(Supervision, RealTimeRestartPolicyRestartsThenGivesUp) {
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/fault_restart.yaml") +
                                   domainOverride(DomainBlock::kSupervision, 3));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("exited with status 3; restarting it (1 of 2)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("restarting it (2 of 2)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run failed: process 'faulty'"), std::string::npos) << r.output;
}

// A launcher killed outright (SIGKILL: it cannot stop its processes) while a component hangs:
// the processes get SIGTERM from the kernel (PR_SET_PDEATHSIG), and the hung one, which cannot
// stop, ends itself after its grace instead of outliving the run forever.
TEST(Supervision, AHungProcessDoesNotOutliveAKilledLauncher) {
  const int domain = testDomain(DomainBlock::kSupervision, 6);
  const std::string log = freshDirectory("killed_launcher") + "/launch.log";
  const pid_t pid = startLaunch(sourcePath("tests/scenes/fault.yaml") + " --set fault.mode=hang --set domain_id=" +
                                    std::to_string(domain) + " --set clock.ack_timeout=60",
                                log, "UAMPC_COMPONENT_PATH=" + binaryPath("tests/components"));
  if (!waitFor([&] { return !processesOfRun(domain, "faulty").empty(); }, std::chrono::seconds(30))) {
    kill(-pid, SIGKILL);
    FAIL() << "the process 'faulty' did not start\n" << readFile(log);
  }
  std::this_thread::sleep_for(std::chrono::seconds(2));  // the component is in its hang by now
  kill(pid, SIGKILL);
  EXPECT_EQ(exitCodeOf(pid), -1);  // killed by the signal
  const bool gone = waitFor([&] { return processesOfRun(domain).empty(); }, std::chrono::seconds(60));
  for (const pid_t left : processesOfRun(domain)) kill(left, SIGKILL);  // not left for the next test
  EXPECT_TRUE(gone) << readFile(log);
  EXPECT_TRUE(logHas(log, "process 'faulty' did not stop within 30 s of being asked to")) << readFile(log);
}

TEST(Supervision, CtrlCStopsEveryProcessCleanly) {
  const std::string log = freshDirectory("ctrl_c") + "/launch.log";
  const pid_t pid =
      startLaunch(sourcePath("tests/scenes/realtime_idle.yaml") + domainOverride(DomainBlock::kSupervision, 4), log);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(pid, SIGINT);  // what Ctrl-C sends to the launcher
  EXPECT_EQ(exitCodeOf(pid), 130) << readFile(log);
  const std::string output = readFile(log);
  EXPECT_NE(output.find("stopped by Ctrl-C"), std::string::npos) << output;
  EXPECT_EQ(output.find("while stopping"), std::string::npos) << output;          // children exited cleanly
  EXPECT_TRUE(processesOfRun(testDomain(DomainBlock::kSupervision, 4)).empty());  // none left behind
}

// A run that a signal cuts short (Slurm's time limit, `docker stop`, systemd send SIGTERM; a
// closed terminal SIGHUP) exits 128 + the signal, as a shell reports it, and its metrics say that
// it did not reach its end. Before, SIGTERM gave 0 and a whole-looking metrics.json, and SIGHUP
// killed the launcher with no summary.
void expectASignalCutsTheRunShort(int signal, int exit_code, const std::string& said, int domain_index) {
  const std::string dir = freshDirectory("cut_by_signal_" + std::to_string(signal));
  const pid_t pid =
      startLaunch(sourcePath("tests/scenes/motor_evaluator.yaml") + " --out " + dir + "/out" +
                      " --set clock.real_time_factor=1" + domainOverride(DomainBlock::kSupervision, domain_index),
                  dir + "/launch.log");
  std::this_thread::sleep_for(std::chrono::seconds(2));
  kill(pid, signal);
  EXPECT_EQ(exitCodeOf(pid), exit_code) << readFile(dir + "/launch.log");
  EXPECT_TRUE(logHas(dir + "/launch.log", "stopped by " + said + "; the run was cut short"))
      << readFile(dir + "/launch.log");
  const auto metrics = run_files::readMetricsFile(dir + "/out/metrics.json");
  ASSERT_TRUE(metrics) << readFile(dir + "/launch.log");
  EXPECT_LT(metrics->sim_time, 30.0);
  EXPECT_EQ(metrics->scene_duration, 30.0);
  EXPECT_EQ(metrics->reached_end, false);
  EXPECT_TRUE(processesOfRun(testDomain(DomainBlock::kSupervision, domain_index)).empty());
}

TEST(Supervision, SigtermCutsTheRunShortWithExitCode143) { expectASignalCutsTheRunShort(SIGTERM, 143, "SIGTERM", 7); }

TEST(Supervision, SighupCutsTheRunShortWithExitCode129) {
  expectASignalCutsTheRunShort(SIGHUP, 129, "SIGHUP (its terminal closed)", 8);
}

// The same scene run to its end says it reached it.
TEST(Supervision, ARunToItsEndSaysItReachedIt) {
  const std::string dir = freshDirectory("run_to_end");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/motor_evaluator.yaml") + " --out " + dir +
                                   domainOverride(DomainBlock::kSupervision, 9));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto metrics = run_files::readMetricsFile(dir + "/metrics.json");
  ASSERT_TRUE(metrics) << r.output;
  EXPECT_EQ(metrics->scene_duration, 30.0);
  EXPECT_EQ(metrics->reached_end, true);
}

}  // namespace
}  // namespace uampc::test
