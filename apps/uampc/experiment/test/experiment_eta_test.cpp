// The experiment's ETA: read from the runs' progress files (written by the clock), computed from sim seconds.
#include <gtest/gtest.h>

#include <filesystem>

#include "experiment/experiment_eta.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_progress.hpp"

namespace uampc::app {
namespace {

TEST(ExperimentEta, ReadsTheProgressFileOfARun) {
  const std::string run = ::testing::TempDir() + "/eta_run";
  std::filesystem::remove_all(run);
  std::filesystem::create_directories(run);
  // Before the clock has written anything: nothing done, length unknown.
  EXPECT_EQ(runProgress(run).done_s, 0.0);
  EXPECT_EQ(runProgress(run).total_s, 0.0);
  run_files::writeRunProgress(run_files::inDirectory(run, run_files::kProgressFile), {46.9, 890.0, 10.9, false});
  const SimProgress p = runProgress(run);
  EXPECT_EQ(p.done_s, 46.9);
  EXPECT_EQ(p.total_s, 890.0);
}

TEST(ExperimentEta, ExtrapolatesSimSecondsPerSlot) {
  // One slot has simulated 100 s in 50 s of wall time (2x real time) and has 300 s left; a
  // pending run of 400 s; two slots: 700 s of sim at 2x on two slots = 175 s.
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds({{{100.0, 400.0}, 50.0}}, {400.0}, 2), 175.0);
  // A pending run of unknown length counts as the mean known length (400 s).
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds({{{100.0, 400.0}, 50.0}}, {-1.0}, 2), 175.0);
  // One run left: one slot works, however many there are.
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds({{{100.0, 400.0}, 50.0}}, {}, 4), 150.0);
  // Finished runs count in the rate, not in what is left.
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds({{{600.0, 600.0}, 100.0}, {{0.0, 600.0}, 0.0}}, {}, 2), 100.0);
  // Nothing simulated yet: no rate, no ETA.
  EXPECT_LT(estimateRemainingSeconds({{{0.0, 400.0}, 3.0}}, {400.0}, 2), 0.0);
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds({{{400.0, 400.0}, 30.0}}, {}, 2), 0.0);
}

}  // namespace
}  // namespace uampc::app
