// The experiment's ETA: read from the launch logs' progress lines, computed from sim seconds.
#include <gtest/gtest.h>

#include "experiment_eta.hpp"

namespace uampc::app {
namespace {

TEST(ExperimentEta, ReadsTheLastProgressLineOfALaunchLog) {
  const std::string log =
      "uampc: scene 'mcd_kth' (6 components, 1 process(es), lockstep, DDS domain 100)\n"
      "uampc: sim 0.0 / 890.0 s (  0%), 0.0x real time\n"
      "[  14.510000] [lo] WARN  degenerate geometry\n"
      "uampc: sim 46.9 / 890.0 s (  5%), 4.3x real time\n";
  const auto p = lastSimProgress(log);
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->done_s, 46.9);
  EXPECT_DOUBLE_EQ(p->total_s, 890.0);
  EXPECT_FALSE(lastSimProgress("uampc: scene 'x'\n[1.0] [lo] INFO sim 3 / 4 s\n"));
  EXPECT_FALSE(lastSimProgress(""));
  // A garbled line is not a progress line (and does not throw).
  EXPECT_FALSE(lastSimProgress("uampc: sim . / .. s\n"));
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
