// The experiment runner's record of a finished run when its markers cannot be written (a full
// disk): no exception (it aborted the experiment before), the reason handed back for the
// experiment to stop on, and no marker that claims what it could not write
// (docs/decisions/run-files-whole-or-absent.md). The disk is full through the file size limit
// (full_disk.hpp: writes fail with EFBIG where a disk gives ENOSPC), set once the run's own files
// are in place.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>

#include "command_runner.hpp"
#include "experiment/backends/experiment_runner.hpp"
#include "full_disk.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"

namespace uampc::app {
namespace {

namespace fs = std::filesystem;

constexpr int kExitedWith0 = 0;       // a wait status: exited with code 0
constexpr int kExitedWith1 = 1 << 8;  // exited with code 1 (WEXITSTATUS)
const SceneEnd kThreeSeconds{3.0, 0.005};  // the end its metrics reach

TEST(ExperimentRunner, AMarkerThatCannotBeWrittenIsReportedNotThrownAndNotLeft) {
  const std::string run = test::freshDirectory("experiment_runner_markers");
  run_files::MetricsDocument metrics;
  metrics.sim_time = 3.0;
  run_files::writeMetricsFile(run_files::inDirectory(run, run_files::kMetricsFile), metrics);
  ASSERT_TRUE(WIFEXITED(kExitedWith1) && WEXITSTATUS(kExitedWith1) == 1);

  RunResult finished, failed;
  std::string finished_error, failed_error;
  {
    test::ScopedFileSizeLimit full_disk(0);
    finished_error = recordRunEnd(run, kExitedWith0, 12.5, false, kThreeSeconds, finished);
    failed_error = recordRunEnd(run, kExitedWith1, 12.5, false, kThreeSeconds, failed);
  }
  const std::string done = run_files::inDirectory(run, run_files::kDoneMarker);
  const std::string failed_marker = run_files::inDirectory(run, run_files::kFailedMarker);
  EXPECT_EQ(finished_error, "cannot write " + done + ": File too large");
  EXPECT_EQ(finished.status, RunStatus::kFailed);  // not done until its marker says so: run again next time
  EXPECT_NE(finished.failure.find("done marker could not be written"), std::string::npos) << finished.failure;
  EXPECT_FALSE(isRunComplete(run, kThreeSeconds));
  EXPECT_EQ(failed_error, "cannot write " + failed_marker + ": File too large");
  EXPECT_EQ(failed.status, RunStatus::kFailed);
  EXPECT_EQ(failed.failure, "exit code 1");
  EXPECT_FALSE(fs::exists(done));
  EXPECT_FALSE(fs::exists(failed_marker));
  EXPECT_FALSE(fs::exists(done + ".partial"));
  EXPECT_FALSE(fs::exists(failed_marker + ".partial"));

  // With room again, the same run is recorded as done.
  RunResult again;
  EXPECT_EQ(recordRunEnd(run, kExitedWith0, 12.5, false, kThreeSeconds, again), "");
  EXPECT_EQ(again.status, RunStatus::kOk);
  EXPECT_TRUE(isRunComplete(run, kThreeSeconds));
}

}  // namespace
}  // namespace uampc::app
