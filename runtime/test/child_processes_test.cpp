#include "uampc/runtime/child_processes.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace uampc {
namespace {

// Far enough that a slow machine never reaches it: these tests assert outcomes, not speed.
ChildProcesses::Clock::time_point farDeadline() { return ChildProcesses::Clock::now() + std::chrono::seconds(60); }

ChildCommand shell(const std::string& name, const std::string& script) {
  return {name, "/bin/sh", {"sh", "-c", script}, std::nullopt, "", "cannot execute /bin/sh\n"};
}

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class ChildProcessesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("uampc_child_processes_test_" + std::to_string(getpid()));
    fs::create_directories(directory_);
  }
  void TearDown() override {
    children_.killAll();
    fs::remove_all(directory_);
  }
  // Waits until the child has written `text` to its log, i.e. it got that far.
  void waitForLog(const fs::path& log, const std::string& text) {
    for (int i = 0; i < 6000 && readText(log).find(text) == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_NE(readText(log).find(text), std::string::npos) << "the child never wrote '" << text << "'";
  }

  fs::path directory_;
  ChildProcesses children_;
};

TEST_F(ChildProcessesTest, ReportsTheExitStatusAndNameOfAChild) {
  const pid_t pid = children_.start(shell("three", "exit 3"));
  EXPECT_EQ(children_.size(), 1u);
  const auto exit = children_.waitForExit(farDeadline());
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(exit->pid, pid);
  EXPECT_EQ(exit->name, "three");
  ASSERT_TRUE(WIFEXITED(exit->status));
  EXPECT_EQ(WEXITSTATUS(exit->status), 3);
  EXPECT_TRUE(children_.empty());
  EXPECT_FALSE(children_.pollExit().has_value());
}

TEST_F(ChildProcessesTest, PassesTheGivenEnvironmentAndWritesTheLogWithStdinClosed) {
  ChildCommand command =
      shell("env", "echo \"greeting=$GREETING other=$OTHER\"; echo to-stderr >&2; read line; echo read=$?");
  command.environment = std::vector<std::string>{"GREETING=hello"};
  command.log_file = (directory_ / "run.log").string();
  setenv("OTHER", "inherited", 1);  // not in the given environment: must not reach the child
  children_.start(command);
  const auto exit = children_.waitForExit(farDeadline());
  unsetenv("OTHER");
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(exit->status, 0);
  // stdin is /dev/null, so read meets end of file (status 1) instead of waiting.
  EXPECT_EQ(readText(directory_ / "run.log"), "greeting=hello other=\nto-stderr\nread=1\n");
}

TEST_F(ChildProcessesTest, InheritsThisProcessEnvironmentWhenNoneIsGiven) {
  setenv("UAMPC_CHILD_PROCESSES_TEST", "inherited", 1);
  children_.start(shell("inherit", "test \"$UAMPC_CHILD_PROCESSES_TEST\" = inherited"));
  const auto exit = children_.waitForExit(farDeadline());
  unsetenv("UAMPC_CHILD_PROCESSES_TEST");
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(exit->status, 0);
}

TEST_F(ChildProcessesTest, AnExecutableThatCannotRunExits127WithTheMessage) {
  ChildCommand command{"missing",    (directory_ / "no-such-program").string(), {"no-such-program"},
                       std::nullopt, (directory_ / "run.log").string(),         "cannot execute no-such-program\n"};
  children_.start(command);
  const auto exit = children_.waitForExit(farDeadline());
  ASSERT_TRUE(exit.has_value());
  ASSERT_TRUE(WIFEXITED(exit->status));
  EXPECT_EQ(WEXITSTATUS(exit->status), 127);
  EXPECT_EQ(readText(directory_ / "run.log"), "cannot execute no-such-program\n");
}

TEST_F(ChildProcessesTest, PollingDoesNotWaitForARunningChildAndSignalAllStopsIt) {
  children_.start(shell("sleeper", "exec sleep 5"));
  EXPECT_FALSE(children_.pollExit().has_value());
  EXPECT_EQ(children_.running().size(), 1u);
  children_.signalAll(SIGTERM);
  const auto exit = children_.waitForExit(farDeadline());
  ASSERT_TRUE(exit.has_value());
  ASSERT_TRUE(WIFSIGNALED(exit->status));
  EXPECT_EQ(WTERMSIG(exit->status), SIGTERM);
}

TEST_F(ChildProcessesTest, AChildIgnoringSigtermOutlivesTheDeadlineAndIsKilled) {
  ChildCommand command = shell("stubborn", "trap '' TERM; echo ready; exec sleep 30");
  command.log_file = (directory_ / "run.log").string();
  children_.start(command);
  waitForLog(directory_ / "run.log", "ready");
  children_.signalAll(SIGTERM);
  EXPECT_FALSE(children_.waitForExit(ChildProcesses::Clock::now() + std::chrono::milliseconds(200)).has_value());
  const auto killed = children_.killAll();
  ASSERT_EQ(killed.size(), 1u);
  EXPECT_EQ(killed[0].name, "stubborn");
  ASSERT_TRUE(WIFSIGNALED(killed[0].status));
  EXPECT_EQ(WTERMSIG(killed[0].status), SIGKILL);
  EXPECT_TRUE(children_.empty());
}

TEST_F(ChildProcessesTest, ReapsOnlyItsOwnChildren) {
  const pid_t other = fork();
  ASSERT_GE(other, 0);
  if (other == 0) _exit(0);
  children_.start(shell("mine", "exit 4"));
  const auto exit = children_.waitForExit(farDeadline());
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(WEXITSTATUS(exit->status), 4);
  int status = 0;
  EXPECT_EQ(waitpid(other, &status, 0), other) << "the pool reaped a child that was not its own";
}

}  // namespace
}  // namespace uampc
