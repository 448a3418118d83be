// Statistics a reviewer accepts for a comparison of two controllers over the same runs: medians
// and quartiles, and the Wilcoxon signed-rank test on paired differences (runs paired by scene
// and seed, so the pair shares the world, the trajectory and the noise).
//
// Wilcoxon signed-rank, two-sided, as R's wilcox.test(x, y, paired = TRUE, correct = TRUE):
// zero differences are dropped (Wilcoxon's convention; n counts the non-zero ones; R drops them
// too but then always uses the normal approximation), |d| ranked with average ranks for ties, W+
// the sum of the ranks of the positive differences.
//  - n <= 25 and no tied |d|: the exact null distribution of W+ (every sign pattern equally
//    likely; counted by dynamic programming over rank sums), p = min(1, 2 min(P(W+ <= w),
//    P(W+ >= w))).
//  - otherwise: normal approximation, mean n(n+1)/4, variance n(n+1)(2n+1)/24 - sum(t^3 - t)/48
//    over groups of t tied |d|, continuity correction 0.5 towards the mean.
// With n pairs the smallest two-sided exact p is 2 / 2^n (0.0625 for 5): few seeds per scene
// cannot be significant on their own, which is why pooling over scenes matters.
#pragma once

#include <cstddef>
#include <vector>

namespace uampc::app {

// Linear interpolation between order statistics (R's type 7, the default of quantile()); NaN
// for no values. q in [0, 1].
double quantile(std::vector<double> values, double q);
double median(std::vector<double> values);

// Ranks of values (1-based), ties given their average rank; sets `ties` to sum(t^3 - t) over
// groups of t equal values (the tie correction of rank tests).
std::vector<double> averageRanks(const std::vector<double>& values, double& ties);

// Spearman's rank correlation (Pearson's on the average ranks); NaN when a series is constant,
// the sizes differ or are below 2.
double spearman(const std::vector<double>& a, const std::vector<double>& b);

struct WilcoxonResult {
  int n = 0;              // non-zero differences used
  int zeros_dropped = 0;  // differences exactly 0
  double w_plus = 0.0;    // sum of the ranks of the positive differences
  double p_value = 0.0;   // two-sided; NaN when n == 0
  bool exact = false;     // exact distribution (else the normal approximation)
};
// Non-finite differences are refused (std::invalid_argument): a pair with a missing figure is
// the caller's to leave out.
WilcoxonResult wilcoxonSignedRank(const std::vector<double>& differences);

// One pair: the controller under test and the baseline on the same scene and seed.
struct RunPair {
  double subject_ate = 0.0, baseline_ate = 0.0;      // m, finite
  double subject_cmplt = 0.0, baseline_cmplt = 0.0;  // NaN when a run has none
  bool subject_lost = false, baseline_lost = false;
};

struct PairedComparison {
  int pairs = 0;
  double median_ate_ratio = 0.0;            // median over pairs of subject / baseline ATE
  double summed_ate_ratio = 0.0;            // sum of the subject's ATE / sum of the baseline's
  double fraction_subject_lower = 0.0;      // pairs where the subject's ATE is lower
  int subject_lost = 0, baseline_lost = 0;  // losses of track among the paired runs
  double median_cmplt_ratio = 0.0;          // median over pairs that both have CMPLT
  WilcoxonResult wilcoxon;                  // on subject - baseline ATE
};
// Every figure NaN (and counts 0) for no pairs.
PairedComparison comparePairs(const std::vector<RunPair>& pairs);

}  // namespace uampc::app
