// The locks of an experiment's output directory (docs/decisions/experiment-output-lock.md): one
// holder at a time, named to whoever is refused; a lock file that is a symbolic link, a directory
// or a FIFO refused without touching what it points to (nor hanging); and an attempt at a run
// that empties its directory, markers and all, but only once it holds the run.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "command_runner.hpp"
#include "experiment/file_lock.hpp"
#include "experiment/run_attempt.hpp"
#include "uampc/run_files/run_directory.hpp"

namespace uampc::app {
namespace {

namespace fs = std::filesystem;

TEST(FileLock, OneHolderAtATimeNamedToTheOthers) {
  const std::string path = test::freshDirectory("file_lock_held") + "/experiment.lock";
  {
    LockAttempt first = lockFile(path, "pid 1 on here (first)");
    ASSERT_TRUE(first.lock) << first.error;
    // Another open file description, as another process has: refused, with what the first wrote.
    const LockAttempt second = lockFile(path, "pid 2 on here (second)");
    EXPECT_FALSE(second.lock);
    EXPECT_EQ(second.held_by, "pid 1 on here (first)");
    EXPECT_EQ(second.error, "");
  }
  EXPECT_TRUE(lockFile(path, "pid 3 on here").lock);  // released with its holder
}

TEST(FileLock, ALockFileThatIsNotARegularFileOfItsOwnIsRefused) {
  const std::string dir = test::freshDirectory("file_lock_not_regular");
  std::ofstream(dir + "/precious.txt") << "keep me\n";
  fs::create_symlink(dir + "/precious.txt", dir + "/link.lock");
  const LockAttempt link = lockFile(dir + "/link.lock", "pid 1 on here");
  EXPECT_FALSE(link.lock);
  EXPECT_EQ(link.error, "cannot lock " + dir + "/link.lock: it is a symbolic link, not a lock file of its own");
  EXPECT_EQ(test::readFile(dir + "/precious.txt"), "keep me\n");
  fs::create_symlink(dir + "/nothing", dir + "/dangling.lock");
  EXPECT_FALSE(lockFile(dir + "/dangling.lock", "").lock);
  EXPECT_FALSE(fs::exists(dir + "/nothing"));  // not made through the link

  fs::create_directory(dir + "/directory.lock");
  EXPECT_EQ(lockFile(dir + "/directory.lock", "").error, "cannot lock " + dir + "/directory.lock: Is a directory");
  ASSERT_EQ(mkfifo((dir + "/fifo.lock").c_str(), 0600), 0);
  EXPECT_EQ(lockFile(dir + "/fifo.lock", "").error, "cannot lock " + dir + "/fifo.lock: it is not a regular file");
}

PlannedRun plannedIn(const std::string& directory) {
  PlannedRun run;
  run.directory = directory;
  return run;
}

TEST(RunAttempt, EmptiesItsDirectoryOnceItHoldsTheRun) {
  const std::string out = test::freshDirectory("run_attempt_empties") + "/out";
  const std::string run = out + "/runs/a/seed1";
  fs::create_directories(run + "/panorama");
  run_files::writeDoneMarker(run, 3.0);
  run_files::writeFailedMarker(run, "exit code 1");
  std::ofstream(run + "/metrics.json") << "{}";
  ASSERT_TRUE(holdsAnAttempt(run));

  AttemptStart held = beginAttempt(out, 0, plannedIn("runs/a/seed1"), "pid 1 on here (first)");
  ASSERT_TRUE(held.lock) << held.error;
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(run)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, (std::vector<std::string>{kAttemptLockFile}));
  EXPECT_FALSE(holdsAnAttempt(run));

  // A second attempt while the first holds it leaves its files alone.
  std::ofstream(run + "/run.log") << "the first attempt's\n";
  const AttemptStart second = beginAttempt(out, 0, plannedIn("runs/a/seed1"), "pid 2 on here");
  EXPECT_FALSE(second.lock);
  EXPECT_EQ(second.held_by, "pid 1 on here (first)");
  EXPECT_EQ(test::readFile(run + "/run.log"), "the first attempt's\n");
}

}  // namespace
}  // namespace uampc::app
