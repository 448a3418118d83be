// Quantiles, the Wilcoxon signed-rank test and the paired comparison against values worked out by
// hand (each test says how), a textbook example, and the edge between exact and approximate p.
#include "uampc/plots/paired_statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace uampc::app {
namespace {

std::vector<double> allPositive(int n) {
  std::vector<double> d;
  for (int i = 1; i <= n; ++i) d.push_back(0.1 * i);
  return d;
}

TEST(Quantile, InterpolatesBetweenOrderStatisticsAsRsDefault) {
  // R: quantile(c(1, 2, 3, 4), c(0.25, 0.5, 1)) = 1.75 2.5 4 (type 7: h = (n - 1) q).
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.25), 1.75);
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(median({7, 1, 3}), 3.0);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 1.0), 4.0);
  EXPECT_TRUE(std::isnan(median({})));
}

TEST(Wilcoxon, AllPositiveGivesTheSmallestExactP) {
  // Every difference positive: W+ = n(n+1)/2, reached by 1 of the 2^n equally likely sign
  // patterns; two-sided p = 2 / 2^n.
  const WilcoxonResult five = wilcoxonSignedRank(allPositive(5));
  EXPECT_TRUE(five.exact);
  EXPECT_EQ(five.n, 5);
  EXPECT_DOUBLE_EQ(five.w_plus, 15);
  EXPECT_DOUBLE_EQ(five.p_value, 2.0 / 32);  // 0.0625: five pairs alone can never reach 0.05
  EXPECT_DOUBLE_EQ(wilcoxonSignedRank(allPositive(6)).p_value, 2.0 / 64);  // 0.03125
  std::vector<double> negative = allPositive(6);
  for (double& d : negative) d = -d;
  EXPECT_DOUBLE_EQ(wilcoxonSignedRank(negative).p_value, 2.0 / 64);  // two-sided: the sign does not matter
  EXPECT_DOUBLE_EQ(wilcoxonSignedRank(negative).w_plus, 0);
}

TEST(Wilcoxon, HollanderAndWolfeDepressionExampleAsInRsDocumentation) {
  // R's ?wilcox.test example (Hollander & Wolfe 1973, p. 29, Hamilton depression scale, first
  // visit x and second visit y): wilcox.test(x, y, paired = TRUE, alternative = "greater") gives
  // V = 40, p-value = 0.01953. By hand: |d| ranks 1..9, the negative differences (-0.08, -0.147)
  // have ranks 2 and 3, so W+ = 45 - 5 = 40; P(W+ >= 40) = P(W- <= 5) = (subsets of 1..9 with
  // sum <= 5: 1 + 1 + 1 + 2 + 2 + 3 = 10) / 512 = 0.01953125; two-sided twice that.
  const std::vector<double> x{1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30};
  const std::vector<double> y{0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29};
  std::vector<double> d;
  for (std::size_t i = 0; i < x.size(); ++i) d.push_back(x[i] - y[i]);
  const WilcoxonResult w = wilcoxonSignedRank(d);
  EXPECT_TRUE(w.exact);
  EXPECT_DOUBLE_EQ(w.w_plus, 40);
  EXPECT_DOUBLE_EQ(w.p_value, 20.0 / 512);
}

TEST(Wilcoxon, ExactDistributionInTheMiddle) {
  // n = 10, positive ranks {1, 3, 4}: W+ = 8. Sign patterns with W+ <= 8 are the subsets of 1..10
  // with sum <= 8, i.e. partitions into distinct parts of 0..8: 1+1+1+2+2+3+4+5+6 = 25. Two-sided
  // p = 2 * 25 / 1024.
  const WilcoxonResult w = wilcoxonSignedRank({1, -2, 3, 4, -5, -6, -7, -8, -9, -10});
  EXPECT_TRUE(w.exact);
  EXPECT_DOUBLE_EQ(w.w_plus, 8);
  EXPECT_DOUBLE_EQ(w.p_value, 50.0 / 1024);
}

TEST(Wilcoxon, SymmetricDifferencesGiveOne) {
  // W+ = 1 + 4 = 5 = n(n+1)/4: the centre of the distribution; P(W+ <= 5) = P(W+ >= 5) = 9/16,
  // p = min(1, 18/16) = 1.
  const WilcoxonResult exact = wilcoxonSignedRank({1, -2, -3, 4});
  EXPECT_TRUE(exact.exact);
  EXPECT_DOUBLE_EQ(exact.p_value, 1.0);
  // Tied magnitudes (normal approximation): z = 0 and no continuity correction at the centre.
  const WilcoxonResult tied = wilcoxonSignedRank({-1, 1, -2, 2});
  EXPECT_FALSE(tied.exact);
  EXPECT_DOUBLE_EQ(tied.p_value, 1.0);
}

TEST(Wilcoxon, ZeroDifferencesAreDropped) {
  // Wilcoxon's convention: the two zeros leave five positive differences, p = 2/32.
  const WilcoxonResult w = wilcoxonSignedRank({0, 0.1, 0.2, 0, 0.3, 0.4, 0.5});
  EXPECT_EQ(w.n, 5);
  EXPECT_EQ(w.zeros_dropped, 2);
  EXPECT_TRUE(w.exact);
  EXPECT_DOUBLE_EQ(w.p_value, 0.0625);
  const WilcoxonResult none = wilcoxonSignedRank({0, 0});
  EXPECT_EQ(none.n, 0);
  EXPECT_TRUE(std::isnan(none.p_value));
}

TEST(Wilcoxon, TiesUseTheNormalApproximationWithTieAndContinuityCorrection) {
  // Seven +1 and one -1: all eight tied, rank 4.5 each; W+ = 31.5, mean 8*9/4 = 18, variance
  // 8*9*17/24 - (8^3 - 8)/48 = 51 - 10.5 = 40.5; z = (13.5 - 0.5) / sqrt(40.5) = 2.04275;
  // p = 2 (1 - Phi(z)) = 0.0410769 (R: wilcox.test(c(rep(1, 7), -1)) with its ties warning).
  const WilcoxonResult w = wilcoxonSignedRank({1, 1, 1, 1, 1, 1, 1, -1});
  EXPECT_FALSE(w.exact);
  EXPECT_DOUBLE_EQ(w.w_plus, 31.5);
  EXPECT_NEAR(w.p_value, 0.0410769029, 1e-9);
}

TEST(Wilcoxon, ExactUpToTwentyFiveThenNormal) {
  EXPECT_TRUE(wilcoxonSignedRank(allPositive(25)).exact);
  EXPECT_DOUBLE_EQ(wilcoxonSignedRank(allPositive(25)).p_value, 2.0 / std::ldexp(1.0, 25));
  // n = 26 all positive: W+ = 351, mean 175.5, variance 26*27*53/24 = 1550.25,
  // z = (175.5 - 0.5) / 39.3732 = 4.44465, p = 8.80367e-6.
  const WilcoxonResult w = wilcoxonSignedRank(allPositive(26));
  EXPECT_FALSE(w.exact);
  EXPECT_NEAR(w.p_value, 8.80366977e-6, 1e-13);
}

TEST(Wilcoxon, RefusesNonFiniteDifferences) {
  EXPECT_THROW(wilcoxonSignedRank({1, std::numeric_limits<double>::quiet_NaN()}), std::invalid_argument);
}

TEST(PairedComparison, RatiosFractionsLossesAndTheTest) {
  // Subject / baseline ATE: 1/4, 3/2, 2/8 -> ratios 0.25, 1.5, 0.25 (median 0.25); sums 6/14.
  // The subject is lower in 2 of 3. CMPLT ratios 1.1 and 0.9 (the third pair has no CMPLT):
  // median 1.0. Differences -3, +1, -6: W+ = 1 (rank of 1), n = 3, P(W+ <= 1) = 2/8, p = 0.5.
  const double none = std::numeric_limits<double>::quiet_NaN();
  const PairedComparison c =
      comparePairs({{1, 4, 110, 100, false, false}, {3, 2, 90, 100, false, true}, {2, 8, none, 100, true, true}});
  EXPECT_EQ(c.pairs, 3);
  EXPECT_DOUBLE_EQ(c.median_ate_ratio, 0.25);
  EXPECT_DOUBLE_EQ(c.summed_ate_ratio, 6.0 / 14);
  EXPECT_DOUBLE_EQ(c.fraction_subject_lower, 2.0 / 3);
  EXPECT_EQ(c.subject_lost, 1);
  EXPECT_EQ(c.baseline_lost, 2);
  EXPECT_DOUBLE_EQ(c.median_cmplt_ratio, 1.0);
  EXPECT_DOUBLE_EQ(c.wilcoxon.w_plus, 1);
  EXPECT_DOUBLE_EQ(c.wilcoxon.p_value, 0.5);
  const PairedComparison empty = comparePairs({});
  EXPECT_EQ(empty.pairs, 0);
  EXPECT_TRUE(std::isnan(empty.median_ate_ratio));
  EXPECT_TRUE(std::isnan(empty.wilcoxon.p_value));
}

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

}  // namespace
}  // namespace uampc::app
