// The run lock in a directory every user may write: a planted link, hard link, FIFO or another
// user's file never makes a launch write, truncate or chmod anything but its own lock file
// (docs/decisions/lock-files-never-followed.md).
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "uampc/runtime/domain_run_lock.hpp"

namespace uampc {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class DomainRunLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("uampc_run_lock_test_" + std::to_string(getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    locks_ = (root_ / "locks").string();
    victim_ = (root_ / "victim.txt").string();
    std::ofstream(victim_) << "precious\n";
    chmod(victim_.c_str(), 0600);
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string lockPath() const { return locks_ + "/run.lock"; }
  std::optional<DomainRunLock> take(const std::string& description = "run A", std::string* holder = nullptr) {
    return DomainRunLock::takeFile(locks_, "run.lock", description, holder);
  }
  // The message of the LockFileError that taking the lock throws; empty if it throws none.
  std::string refusal() {
    try {
      take();
    } catch (const LockFileError& e) {
      return e.what();
    }
    return {};
  }
  void expectVictimUntouched() const {
    std::stringstream text;
    text << std::ifstream(victim_).rdbuf();
    EXPECT_EQ(text.str(), "precious\n");
    struct stat st {};
    ASSERT_EQ(stat(victim_.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);
  }

  fs::path root_;
  std::string locks_, victim_;
};

TEST_F(DomainRunLockTest, MakesItsDirectoryStickyAndWorldWritableAndItsFileOnlyItsOwnToWrite) {
  auto lock = take("uampc launch a.yaml, pid 1");
  ASSERT_TRUE(lock);
  struct stat dir {
  }, file{};
  ASSERT_EQ(lstat(locks_.c_str(), &dir), 0);
  EXPECT_EQ(dir.st_mode & 07777, 01777u);
  ASSERT_EQ(lstat(lockPath().c_str(), &file), 0);
  EXPECT_EQ(file.st_mode & 022, 0u);  // others read who holds it; only its maker writes it
  std::string holder;
  EXPECT_FALSE(take("run B", &holder));
  EXPECT_EQ(holder, "uampc launch a.yaml, pid 1");
}

TEST_F(DomainRunLockTest, ASymbolicLinkIsRefusedAndItsTargetUntouched) {
  fs::create_directories(locks_);
  fs::create_symlink(victim_, lockPath());
  EXPECT_THAT(refusal(), HasSubstr(lockPath() + ": it is a symbolic link"));
  expectVictimUntouched();
}

TEST_F(DomainRunLockTest, ADanglingLinkIsRefusedAndCreatesNothing) {
  fs::create_directories(locks_);
  const fs::path target = root_ / "missing" / "made.lock";
  fs::create_symlink(target, lockPath());
  EXPECT_THAT(refusal(), HasSubstr("symbolic link"));
  EXPECT_FALSE(fs::exists(target));
  fs::create_directories(root_ / "missing");
  EXPECT_THAT(refusal(), HasSubstr("symbolic link"));
  EXPECT_FALSE(fs::exists(target));
}

TEST_F(DomainRunLockTest, AHardLinkToAnotherFileIsRefused) {
  fs::create_directories(locks_);
  fs::create_hard_link(victim_, lockPath());
  EXPECT_THAT(refusal(), HasSubstr("2 hard links"));
  expectVictimUntouched();
}

TEST_F(DomainRunLockTest, AFifoIsRefusedWithoutBlocking) {
  fs::create_directories(locks_);
  ASSERT_EQ(mkfifo(lockPath().c_str(), 0666), 0);
  EXPECT_THAT(refusal(), HasSubstr("not a regular file"));
}

TEST_F(DomainRunLockTest, ADirectoryThatIsALinkIsRefused) {
  fs::create_directories(root_ / "elsewhere");
  fs::create_directory_symlink(root_ / "elsewhere", locks_);
  EXPECT_THAT(refusal(), HasSubstr(locks_ + ": it is not a directory"));
  EXPECT_TRUE(fs::is_empty(root_ / "elsewhere"));
}

TEST_F(DomainRunLockTest, AFileInADirectoryThatCannotBeMadeIsRefused) {
  locks_ = (root_ / "no" / "such" / "dir").string();
  EXPECT_THAT(refusal(), HasSubstr("cannot create it"));
}

// Another user's lock file is locked (flock needs no write access) but never written, truncated
// or chmodded. Needs root to make a file of another user; skipped otherwise.
TEST_F(DomainRunLockTest, AnotherUsersFileIsLockedButNeverWritten) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to chown a file to another user";
  fs::create_directories(locks_);
  std::ofstream(lockPath()) << "theirs\n";
  ASSERT_EQ(chmod(lockPath().c_str(), 0600), 0);
  ASSERT_EQ(chown(lockPath().c_str(), 65534, 65534), 0);
  auto lock = take("mine");
  ASSERT_TRUE(lock);
  std::stringstream text;
  text << std::ifstream(lockPath()).rdbuf();
  EXPECT_EQ(text.str(), "theirs\n");
  struct stat st {};
  ASSERT_EQ(stat(lockPath().c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
}

TEST_F(DomainRunLockTest, WhatAHolderWroteIsPrintedWithItsControlBytesEscaped) {
  fs::create_directories(locks_);
  std::ofstream(lockPath()) << "evil \x1b[2J\x07 run\n";
  const int other = open(lockPath().c_str(), O_RDONLY);
  ASSERT_EQ(flock(other, LOCK_EX | LOCK_NB), 0);
  std::string holder;
  EXPECT_FALSE(take("mine", &holder));
  EXPECT_EQ(holder.find('\x1b'), std::string::npos) << holder;
  EXPECT_EQ(holder.find('\x07'), std::string::npos) << holder;
  EXPECT_THAT(holder, HasSubstr("evil"));
  close(other);
}

}  // namespace
}  // namespace uampc
