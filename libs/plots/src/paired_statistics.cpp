#include "uampc/plots/paired_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace uampc::app {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kLargestExactN = 25;

// Number of sign patterns of ranks 1..n whose positive ranks sum to s, for s = 0 .. n(n+1)/2.
// At most 2^25 patterns: exact in a double.
std::vector<double> signedRankCounts(int n) {
  std::vector<double> counts(n * (n + 1) / 2 + 1, 0.0);
  counts[0] = 1.0;
  int reachable = 0;
  for (int rank = 1; rank <= n; ++rank) {
    reachable += rank;
    for (int s = reachable; s >= rank; --s) counts[s] += counts[s - rank];
  }
  return counts;
}

double exactTwoSidedP(int n, double w_plus) {
  const std::vector<double> counts = signedRankCounts(n);
  const auto w = static_cast<long>(std::lround(w_plus));  // integer: no ties
  double below = 0.0, above = 0.0;                        // P(W+ <= w), P(W+ >= w) as counts
  for (long s = 0; s < static_cast<long>(counts.size()); ++s) {
    if (s <= w) below += counts[s];
    if (s >= w) above += counts[s];
  }
  return std::min(1.0, 2.0 * std::min(below, above) / std::ldexp(1.0, n));
}

double normalTwoSidedP(int n, double w_plus, double ties) {
  const double nn = n;
  const double centred = w_plus - nn * (nn + 1) / 4;
  const double sigma = std::sqrt(nn * (nn + 1) * (2 * nn + 1) / 24 - ties / 48);
  const double correction = centred > 0 ? 0.5 : (centred < 0 ? -0.5 : 0.0);
  const double z = (centred - correction) / sigma;
  return std::min(1.0, std::erfc(std::abs(z) / std::sqrt(2.0)));  // 2 (1 - Phi(|z|))
}

}  // namespace

// Ranks of values (1-based), ties given their average rank; sets `ties` to sum(t^3 - t) over
// groups of t equal values.
std::vector<double> averageRanks(const std::vector<double>& values, double& ties) {
  std::vector<std::size_t> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(values.size());
  ties = 0.0;
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin + 1;
    while (end < order.size() && values[order[end]] == values[order[begin]]) ++end;
    const double rank = (begin + 1 + end) / 2.0;  // average of ranks begin+1 .. end
    for (std::size_t k = begin; k < end; ++k) ranks[order[k]] = rank;
    const double t = static_cast<double>(end - begin);
    ties += t * t * t - t;
    begin = end;
  }
  return ranks;
}

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (a.size() != b.size() || a.size() < 2) return nan;
  double ties_a = 0.0, ties_b = 0.0;
  const std::vector<double> ra = averageRanks(a, ties_a), rb = averageRanks(b, ties_b);
  const double mean = (double(a.size()) + 1.0) / 2.0;  // of ranks 1..n, ties or not
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    ab += (ra[i] - mean) * (rb[i] - mean);
    aa += (ra[i] - mean) * (ra[i] - mean);
    bb += (rb[i] - mean) * (rb[i] - mean);
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : nan;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double h = (values.size() - 1) * std::clamp(q, 0.0, 1.0);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - lo) * (values[hi] - values[lo]);
}

double median(std::vector<double> values) { return quantile(std::move(values), 0.5); }

WilcoxonResult wilcoxonSignedRank(const std::vector<double>& differences) {
  WilcoxonResult result;
  std::vector<double> magnitudes, signs;
  for (double d : differences) {
    if (!std::isfinite(d))
      throw std::invalid_argument("wilcoxonSignedRank: non-finite difference " + std::to_string(d));
    if (d == 0.0) {
      ++result.zeros_dropped;
      continue;
    }
    magnitudes.push_back(std::abs(d));
    signs.push_back(d > 0 ? 1.0 : -1.0);
  }
  result.n = static_cast<int>(magnitudes.size());
  if (result.n == 0) {
    result.p_value = kNaN;
    return result;
  }
  double ties = 0.0;
  const std::vector<double> ranks = averageRanks(magnitudes, ties);
  for (std::size_t i = 0; i < ranks.size(); ++i) {
    if (signs[i] > 0) result.w_plus += ranks[i];
  }
  result.exact = result.n <= kLargestExactN && ties == 0.0;
  result.p_value =
      result.exact ? exactTwoSidedP(result.n, result.w_plus) : normalTwoSidedP(result.n, result.w_plus, ties);
  return result;
}

PairedComparison comparePairs(const std::vector<RunPair>& pairs) {
  PairedComparison c;
  c.pairs = static_cast<int>(pairs.size());
  std::vector<double> ate_ratios, cmplt_ratios, differences;
  double subject_sum = 0.0, baseline_sum = 0.0;
  int lower = 0;
  for (const RunPair& p : pairs) {
    if (p.baseline_ate > 0) ate_ratios.push_back(p.subject_ate / p.baseline_ate);
    subject_sum += p.subject_ate;
    baseline_sum += p.baseline_ate;
    lower += p.subject_ate < p.baseline_ate;
    c.subject_lost += p.subject_lost;
    c.baseline_lost += p.baseline_lost;
    if (std::isfinite(p.subject_cmplt) && std::isfinite(p.baseline_cmplt) && p.baseline_cmplt > 0)
      cmplt_ratios.push_back(p.subject_cmplt / p.baseline_cmplt);
    differences.push_back(p.subject_ate - p.baseline_ate);
  }
  c.median_ate_ratio = median(ate_ratios);
  c.summed_ate_ratio = baseline_sum > 0 ? subject_sum / baseline_sum : kNaN;
  c.fraction_subject_lower = c.pairs ? static_cast<double>(lower) / c.pairs : kNaN;
  c.median_cmplt_ratio = median(cmplt_ratios);
  c.wilcoxon = wilcoxonSignedRank(differences);
  return c;
}

}  // namespace uampc::app
