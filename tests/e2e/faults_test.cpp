// Faults a run survives (docs/user/faults.md): the launcher killed, a process group killed or
// stopped, two runs on one DDS domain, an output directory that cannot be written or disappears,
// a disk that fills up, a component that fails while shutting down.
// Each is detected and named, nothing hangs, and what was written stays valid.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "full_disk.hpp"
#include "test_domains.hpp"
#include "uampc/run_files/csv.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_progress.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

// A lockstep run of two process groups (motor, control) that runs until something ends it.
pid_t startLongRun(int domain, const std::string& dir, const std::string& extra = "") {
  return startLaunch(sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " + dir + "/out" +
                         " --set clock.duration=600" + extra + " --set domain_id=" + std::to_string(domain),
                     dir + "/launch.log", std::string(run_files::kProgressFileVariable) + "=" + dir + "/progress.json");
}

bool simTimeHasPassed(const std::string& dir) {
  return waitFor(
      [&] {
        const auto p = run_files::readRunProgress(dir + "/progress.json");
        return p && p->sim_s > 0.5;
      },
      seconds(60));
}

// Kills the launcher only (not its process group) and reports how long its children took to stop.
void expectChildrenStopWhenTheLauncherIsKilled(pid_t launcher, int domain, const std::string& what) {
  ASSERT_EQ(processesOfRun(domain).size(), 2u);
  kill(launcher, SIGKILL);
  waitpid(launcher, nullptr, 0);
  const auto start = std::chrono::steady_clock::now();
  const bool stopped = waitFor([&] { return processesOfRun(domain).empty(); }, seconds(20));
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(stopped) << what << ": children still running 20 s after the launcher was killed";
  std::cout << what << ": children stopped " << elapsed << " s after the launcher was killed\n";
  if (!stopped) {
    for (pid_t pid : processesOfRun(domain)) kill(pid, SIGKILL);
  }
}

TEST(Faults, LockstepChildrenStopWhenTheLauncherIsKilled) {
  const int domain = testDomain(DomainBlock::kFaults, 0);
  const std::string dir = freshDirectory("faults_launcher_killed_lockstep");
  const pid_t launcher = startLongRun(domain, dir);
  ASSERT_TRUE(simTimeHasPassed(dir)) << readFile(dir + "/launch.log");
  expectChildrenStopWhenTheLauncherIsKilled(launcher, domain, "lockstep");
}

TEST(Faults, RealTimeChildrenStopWhenTheLauncherIsKilled) {
  const int domain = testDomain(DomainBlock::kFaults, 1);
  const std::string dir = freshDirectory("faults_launcher_killed_realtime");
  const pid_t launcher =
      startLaunch(sourcePath("tests/scenes/realtime_idle.yaml") + " --set domain_id=" + std::to_string(domain),
                  dir + "/launch.log");
  ASSERT_TRUE(waitFor([&] { return processesOfRun(domain).size() == 2; }, seconds(30)));
  std::this_thread::sleep_for(seconds(1));  // running, commanding the motor
  expectChildrenStopWhenTheLauncherIsKilled(launcher, domain, "real time");
}

// A second launch on a domain where a run is going is refused before it starts anything, and the
// run already there goes on untouched (docs/decisions/one-run-per-domain.md).
TEST(Faults, ASecondRunOnADomainIsRefusedAndTheFirstGoesOn) {
  const int domain = testDomain(DomainBlock::kFaults, 2);
  const std::string dir = freshDirectory("faults_two_runs");
  const pid_t first = startLongRun(domain, dir);
  ASSERT_TRUE(simTimeHasPassed(dir)) << readFile(dir + "/launch.log");
  const CommandResult second =
      runUampc("launch " + sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " + dir +
               "/second --set clock.duration=2 --set domain_id=" + std::to_string(domain));
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_NE(second.output.find("another run is on DDS domain " + std::to_string(domain) + " (uampc launch " +
                               sourcePath("tests/scenes/motor_two_processes.yaml") + ", pid " + std::to_string(first)),
            std::string::npos)
      << second.output;
  EXPECT_NE(second.output.find("nothing was started"), std::string::npos) << second.output;
  EXPECT_FALSE(fs::exists(dir + "/second/run_info.json"));
  // The first run goes on: 2 s of sim time more, then it is stopped as a user would, cleanly.
  const double before = run_files::readRunProgress(dir + "/progress.json")->sim_s;
  EXPECT_TRUE(waitFor(
      [&] {
        const auto p = run_files::readRunProgress(dir + "/progress.json");
        return p && p->sim_s > before + 2.0;
      },
      seconds(60)))
      << readFile(dir + "/launch.log");
  kill(first, SIGINT);
  EXPECT_EQ(exitCodeOf(first), 130) << readFile(dir + "/launch.log");
  EXPECT_FALSE(logHas(dir + "/launch.log", "another lockstep run")) << readFile(dir + "/launch.log");
  EXPECT_FALSE(logHas(dir + "/launch.log", "another run")) << readFile(dir + "/launch.log");
}

// The run lock's directory is shared by every user: a link planted at a lock file's path (to a
// file of the user who launches, or dangling into a directory that does not exist) makes the launch
// refuse, naming the path, and the file it points to is neither written, truncated nor chmodded
// nor created. Before, the launch opened it with O_CREAT through the link, made it 0666 and wrote
// its description into it (docs/decisions/lock-files-never-followed.md).
TEST(Faults, ALinkPlantedAtTheRunLockIsNeverFollowed) {
  const int domain = testDomain(DomainBlock::kFaults, 9);
  const std::string dir = freshDirectory("faults_planted_lock_link");
  const std::string victim = dir + "/victim.txt";
  std::ofstream(victim) << "precious\n";
  fs::permissions(victim, fs::perms::owner_read | fs::perms::owner_write);
  // The documented location (docs/user/faults.md).
  const std::string lock = "/tmp/uampc/run-on-domain-" + std::to_string(domain) + ".lock";
  if (fs::create_directories("/tmp/uampc")) fs::permissions("/tmp/uampc", fs::perms(01777));  // as a launch makes it
  for (const std::string& target : {victim, dir + "/missing/made.lock"}) {
    fs::remove(lock);
    fs::create_symlink(target, lock);
    const CommandResult r =
        runUampc("launch " + sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " + dir +
                 "/out --overwrite --set clock.duration=1 --set domain_id=" + std::to_string(domain));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("cannot use the lock file " + lock + ": it is a symbolic link"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("nothing was started"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir + "/out/run_info.json"));
  }
  fs::remove(lock);
  EXPECT_EQ(readFile(victim), "precious\n");
  EXPECT_EQ(fs::status(victim).permissions(), fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_FALSE(fs::exists(dir + "/missing"));
}

TEST(Faults, AProcessGroupKilledMidRunIsNamedAndLeavesNothingBehind) {
  const int domain = testDomain(DomainBlock::kFaults, 3);
  const std::string dir = freshDirectory("faults_process_killed");
  const pid_t launcher = startLongRun(domain, dir);
  ASSERT_TRUE(simTimeHasPassed(dir)) << readFile(dir + "/launch.log");
  const auto motor = processesOfRun(domain, "motor");
  ASSERT_EQ(motor.size(), 1u);
  kill(motor[0], SIGKILL);
  EXPECT_EQ(exitCodeOf(launcher), 1);
  const std::string log = readFile(dir + "/launch.log");
  EXPECT_NE(log.find("process 'motor' (pid " + std::to_string(motor[0]) + ") killed by signal 9"), std::string::npos)
      << log;
  // Its Fast DDS segments (at least its own) are gone.
  EXPECT_NE(log.find("shared-memory segment(s) that killed processes left in /dev/shm"), std::string::npos) << log;
  // What the other process wrote is whole: every row of the recording parses, times increase.
  const auto rows = run_files::readCsv(dir + "/out/recorder_motor_states.csv").rows;
  ASSERT_GT(rows.size(), 50u);
  for (std::size_t i = 1; i < rows.size(); ++i) ASSERT_GT(rows[i][0], rows[i - 1][0]) << "row " << i;
  // The next run on the same domain starts and ends normally.
  const CommandResult next = runUampc("launch " + sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " +
                                      dir + "/next --set clock.duration=1 --set domain_id=" + std::to_string(domain));
  EXPECT_EQ(next.exit_code, 0) << next.output;
}

TEST(Faults, AStoppedProcessGroupIsNamedByTheAcknowledgementTimeout) {
  const int domain = testDomain(DomainBlock::kFaults, 4);
  const std::string dir = freshDirectory("faults_process_stopped");
  // The peer gives up at 0.9 x ack_timeout, the clock at 1 x: at 6 s the peer's report has 0.6 s to
  // arrive first even on a loaded machine (2 s left 0.2 s, which a CI run under load missed).
  const pid_t launcher = startLongRun(domain, dir, " --set clock.ack_timeout=6");
  ASSERT_TRUE(simTimeHasPassed(dir)) << readFile(dir + "/launch.log");
  const auto motor = processesOfRun(domain, "motor");
  ASSERT_EQ(motor.size(), 1u);
  kill(motor[0], SIGSTOP);
  EXPECT_EQ(exitCodeOf(launcher), 1);
  // The stopped process is named, by the clock or by the other process waiting for its
  // acknowledgement (whichever waited when it stopped), and only it.
  EXPECT_TRUE(logHas(dir + "/launch.log", "from process(es) motor ")) << readFile(dir + "/launch.log");
  EXPECT_FALSE(logHas(dir + "/launch.log", "process(es) motor, control")) << readFile(dir + "/launch.log");
  kill(motor[0], SIGKILL);  // killed by the launcher already; in case it was not
}

TEST(Faults, AnOutputDirectoryThatCannotBeCreatedStartsNothing) {
  const std::string dir = freshDirectory("faults_out_unwritable");
  std::ofstream(dir + "/a_file") << "not a directory";
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " + dir +
                                   "/a_file/out --set clock.duration=1" + domainOverride(DomainBlock::kFaults, 5));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(dir + "/a_file/out"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("nothing was started"), std::string::npos) << r.output;
}

TEST(Faults, AnOutputDirectoryRemovedDuringTheRunStopsItWithTheReason) {
  const int domain = testDomain(DomainBlock::kFaults, 6);
  const std::string dir = freshDirectory("faults_out_removed");
  const pid_t launcher = startLongRun(domain, dir);
  ASSERT_TRUE(simTimeHasPassed(dir)) << readFile(dir + "/launch.log");
  fs::remove_all(dir + "/out");
  EXPECT_EQ(exitCodeOf(launcher), 1);
  const std::string log = readFile(dir + "/launch.log");
  EXPECT_NE(log.find("the output directory " + dir + "/out was removed during the run"), std::string::npos) << log;
  EXPECT_EQ(log.find("while stopping"), std::string::npos) << log;  // the processes stopped cleanly
  EXPECT_TRUE(processesOfRun(domain).empty());
}

// A launch into a directory that holds a run replaced it silently; it is refused, naming the file
// that shows the run and the option, unless --overwrite is given. An empty existing directory is
// fine (docs/decisions/no-silent-overwrite.md).
TEST(Faults, AnOutputDirectoryHoldingARunIsRefusedUnlessOverwriteIsGiven) {
  const std::string out = freshDirectory("faults_out_holds_a_run");  // exists, empty
  const std::string launch = "launch " + sourcePath("tests/scenes/motor_two_processes.yaml") + " --out " + out +
                             " --set clock.duration=0.5" + domainOverride(DomainBlock::kFaults, 7);
  const CommandResult first = runUampc(launch);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string record = run_files::inDirectory(out, run_files::kRunInfoFile);
  const std::string before = readFile(record);
  const CommandResult again = runUampc(launch + " --set seed=2");
  EXPECT_EQ(again.exit_code, 1) << again.output;
  EXPECT_NE(again.output.find("--out " + out + " already holds a run (" + record + "); give --overwrite"),
            std::string::npos)
      << again.output;
  EXPECT_NE(again.output.find("nothing was started"), std::string::npos) << again.output;
  EXPECT_EQ(readFile(record), before);
  // metrics.json alone says so too (a run whose record was removed).
  fs::remove(record);
  std::ofstream(run_files::inDirectory(out, run_files::kMetricsFile)) << "{}";
  EXPECT_EQ(runUampc(launch).exit_code, 1);
  const CommandResult overwritten = runUampc(launch + " --set seed=2 --overwrite");
  EXPECT_EQ(overwritten.exit_code, 0) << overwritten.output;
  EXPECT_NE(readFile(record).find("\"seed\": 2"), std::string::npos) << readFile(record);
}

// `uampc record -o EXISTING.mcap` replaced a 50 MB recording with a 165-byte one; it is refused
// before anything is recorded, unless --overwrite is given.
TEST(Faults, RecordRefusesAnExistingFileUnlessOverwriteIsGiven) {
  const std::string dir = freshDirectory("faults_record_existing");
  const std::string file = dir + "/earlier.mcap";
  std::ofstream(file) << "an earlier recording";
  const std::string record =
      "record -o " + file + " --duration 0.2 --domain " + std::to_string(testDomain(DomainBlock::kFaults, 8));
  const CommandResult refused = runUampc(record);
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(refused.output.find(file + " exists; give --overwrite to replace it"), std::string::npos) << refused.output;
  EXPECT_EQ(readFile(file), "an earlier recording");
  const CommandResult replaced = runUampc(record + " --overwrite");
  EXPECT_EQ(replaced.exit_code, 0) << replaced.output;
  EXPECT_NE(readFile(file), "an earlier recording");
  // A new file needs no option.
  EXPECT_EQ(runUampc("record -o " + dir + "/new.mcap --duration 0.2 --domain " +
                     std::to_string(testDomain(DomainBlock::kFaults, 8)))
                .exit_code,
            0);
}

// The disk fills up during the run (full_disk.hpp: files limited to 32 KB; motor.csv reaches it
// after about 3.5 of the 30 simulated seconds, the run's other files stay below it). The run stops
// there with the file and the reason named, and leaves no metrics.json: with its time series cut,
// the run is not complete (docs/decisions/run-files-whole-or-absent.md). Before, it ran to the end
// and wrote a metrics.json of the whole 30 s beside a motor.csv cut short.
TEST(Faults, AFullDiskStopsTheRunNamingTheFileAndLeavesNoMetrics) {
  const std::string dir = freshDirectory("faults_full_disk");
  const std::string out = dir + "/out";
  const CommandResult r = runShell(withFileSizeLimit(
      32 * 1024, "UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " + binaryPath("bin/uampc") + " launch " +
                     sourcePath("tests/scenes/motor_evaluator.yaml") + " --out " + out +
                     domainOverride(DomainBlock::kFaults, 7)));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("component 'evaluator' failed in input 'motor_state'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cannot write " + out + "/motor.csv: File too large"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out + "/" + run_files::kMetricsFile));
  for (const auto& entry : fs::directory_iterator(out)) EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  const auto rows = run_files::readCsv(out + "/motor.csv").rows;  // what reached the disk reads back
  ASSERT_FALSE(rows.empty());
  EXPECT_LT(rows.back()[0], 30.0);  // cut where the disk filled: the run did not go on
}

// A component that fails while shutting down (as the evaluator does when its last write finds the
// disk full) fails the run, and the components after it still shut down and write their files.
// Before, the first failure skipped the others: the evaluator here wrote no metrics.json.
TEST(Faults, AComponentFailingAtShutdownLetsTheOthersWriteTheirFiles) {
  const std::string dir = freshDirectory("faults_shutdown_failure");
  const CommandResult r = runUampc("launch " + sourcePath("tests/scenes/shutdown_failure.yaml") + " --out " + dir +
                                   "/out" + domainOverride(DomainBlock::kFaults, 8));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("component 'fault' failed while shutting down: injected failure at shutdown"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::is_regular_file(dir + "/out/" + run_files::kMetricsFile)) << r.output;
}

}  // namespace
}  // namespace uampc::test
