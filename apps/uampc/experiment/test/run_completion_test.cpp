// What counts as a done run (docs/decisions/experiment-run-done.md): exited 0 with metrics whose
// sim time reached the scene's end within a step; anything short of it, or a directory with both
// markers, is not done, and the runner records it as failed with how far it got.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "command_runner.hpp"
#include "experiment/backends/experiment_runner.hpp"
#include "experiment/run_completion.hpp"
#include "uampc/run_files/metrics_file.hpp"
#include "uampc/run_files/run_directory.hpp"

namespace uampc::app {
namespace {

const SceneEnd kTwentySeconds{20.0, 0.005};
constexpr int kStatusOfExit0 = 0;  // a wait status

std::string runWithMetrics(const std::string& name, double sim_time) {
  const std::string run = test::freshDirectory(name);
  run_files::MetricsDocument metrics;
  metrics.sim_time = sim_time;
  run_files::writeMetricsFile(run_files::inDirectory(run, run_files::kMetricsFile), metrics);
  return run;
}

TEST(RunCompletion, TheSceneEndIsReachedWithinOneStep) {
  EXPECT_TRUE(reachesSceneEnd(20.0, kTwentySeconds));
  EXPECT_TRUE(reachesSceneEnd(19.995, kTwentySeconds));         // the last step may fall one short
  EXPECT_TRUE(reachesSceneEnd(19.9949999999, kTwentySeconds));  // and a rounding below it
  EXPECT_FALSE(reachesSceneEnd(19.99, kTwentySeconds));
  EXPECT_FALSE(reachesSceneEnd(13.9, kTwentySeconds));
  EXPECT_FALSE(reachesSceneEnd(std::nan(""), kTwentySeconds));
}

TEST(RunCompletion, ADoneMarkerIsNotEnoughWhenTheMetricsStopShort) {
  const std::string run = runWithMetrics("run_completion_short", 13.9);
  run_files::writeDoneMarker(run, 4.0);
  const RunCompletion completion = runCompletion(run, kTwentySeconds);
  EXPECT_EQ(completion.state, RunState::kFailed);
  EXPECT_EQ(completion.reason, "cut short: sim time 13.9 s of 20 s");
  EXPECT_TRUE(isRunComplete(run, SceneEnd{13.9, 0.005}));  // the same run, of a 13.9 s scene
}

TEST(RunCompletion, BothMarkersAreNotDone) {
  const std::string run = runWithMetrics("run_completion_both", 20.0);
  run_files::writeDoneMarker(run, 4.0);
  ASSERT_TRUE(isRunComplete(run, kTwentySeconds));
  run_files::writeFailedMarker(run, "exit code 1");
  const RunCompletion completion = runCompletion(run, kTwentySeconds);
  EXPECT_EQ(completion.state, RunState::kFailed);
  EXPECT_EQ(completion.reason, "both a done and a failed marker (exit code 1)");
}

TEST(RunCompletion, NoMarkerIsUnfinished) {
  const std::string run = runWithMetrics("run_completion_unfinished", 20.0);
  EXPECT_EQ(runCompletion(run, kTwentySeconds).state, RunState::kUnfinished);
}

// The reported case: the launcher got SIGTERM, exited 0 and wrote metrics of 13.9 s of 20.
TEST(RunCompletion, ARunThatExitsZeroShortOfItsEndIsRecordedFailed) {
  const std::string run = runWithMetrics("run_completion_exit_0_short", 13.9);
  RunResult result;
  EXPECT_EQ(recordRunEnd(run, kStatusOfExit0, 5.0, false, kTwentySeconds, result), "");
  EXPECT_EQ(result.status, RunStatus::kFailed);
  EXPECT_EQ(result.failure, "exit code 0, cut short: sim time 13.9 s of 20 s");
  EXPECT_DOUBLE_EQ(result.metrics.sim_time_s, 13.9);  // how far it got, in results.json
  EXPECT_EQ(test::readFile(run_files::inDirectory(run, run_files::kFailedMarker)), result.failure + "\n");
  EXPECT_FALSE(isRunComplete(run, kTwentySeconds));

  constexpr int kStatusOfExit143 = 143 << 8;  // the launcher's exit code when cut by SIGTERM
  RunResult terminated;
  recordRunEnd(run, kStatusOfExit143, 5.0, false, kTwentySeconds, terminated);
  EXPECT_EQ(terminated.failure, "exit code 143, cut short: sim time 13.9 s of 20 s");
}

}  // namespace
}  // namespace uampc::app
