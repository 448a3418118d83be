// The U check measures what it claims: ranks with ties, and on the campus' poor row (where the
// motor angle decides what the LO sees) the registration keeps much more of a wrong start at
// some angles than at others, and U ranks the angles the same way.
#include "uncertainty_check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "simulated_lidar.hpp"

namespace uampc::tools {
namespace {

TEST(Spearman, RanksNotValues) {
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 200, 3000, 40000}), 1.0);
  EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
}

TEST(Spearman, TiesShareTheirMeanRank) {
  // Ranks (1, 2.5, 2.5, 4) against (1, 2, 3, 4): 4.5 / sqrt(4.5 * 5) = 0.9487.
  EXPECT_NEAR(spearman({1, 2, 2, 3}, {1, 2, 3, 4}), 4.5 / std::sqrt(22.5), 1e-12);
}

TEST(Spearman, UndefinedIsNaN) {
  EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));
  EXPECT_TRUE(std::isnan(spearman({1, 2}, {1, 2, 3})));
  EXPECT_TRUE(std::isnan(spearman({1}, {1})));
}

TEST(UncertaintyCheck, RefusesProbesWithoutWarmUpOrPastThePath) {
  const world::World world = world::buildWorld(worldSettingsFor("corridor"));
  UncertaintyCheck check(world, UncertaintyCheckConfig{});
  EXPECT_THROW(check.probe(0.05), std::invalid_argument);
  EXPECT_THROW(check.probe(world.trajectory.endTime() + 1.0), std::invalid_argument);
  UncertaintyCheckConfig no_trials;
  no_trials.trials = 0;
  EXPECT_THROW(UncertaintyCheck(world, no_trials), std::invalid_argument);
}

TEST(UncertaintyCheck, CampusPoorRowAnglesDifferAndURanksThem) {
  const world::World world = world::buildWorld(worldSettingsFor("campus"));
  UncertaintyCheckConfig config;
  config.warmup = 6.0;
  config.trials = 3;
  UncertaintyCheck check(world, config);
  const ProbeResult r = check.probe(106.0);  // the path enters the row of poor blocks (README)
  ASSERT_FALSE(r.lo_lost);
  ASSERT_EQ(r.angles.size(), 72u);  // the controller's 5-degree samples over one turn
  double least = INFINITY, most = 0.0;
  for (const AngleCheck& a : r.angles)
    least = std::min(least, a.mean_square_error), most = std::max(most, a.mean_square_error);
  // The start was off by 0.1 m and 0.5 degrees per axis (mean square 0.030): the best views
  // remove nearly all of it, the worst keep a good part.
  EXPECT_LT(least, 0.003);
  EXPECT_GT(most, 0.01);
  EXPECT_GT(r.spearman_trace, 0.5);
  EXPECT_GT(r.spearman_error, 0.4);
  EXPECT_GT(r.spearman_oracle_trace, r.spearman_trace);  // the criterion itself ranks better
}

}  // namespace
}  // namespace uampc::tools
