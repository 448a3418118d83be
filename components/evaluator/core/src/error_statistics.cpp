#include "uampc/evaluator/error_statistics.hpp"

#include <algorithm>
#include <cmath>

namespace uampc::evaluator {

ErrorStatistics summarize(std::vector<double> errors) {
  ErrorStatistics stats;
  stats.count = errors.size();
  if (errors.empty()) return stats;
  double sum = 0.0;
  double sum_squares = 0.0;
  double max = errors.front();
  for (const double e : errors) {
    sum += e;
    sum_squares += e * e;
    max = std::max(max, e);
  }
  const double n = static_cast<double>(errors.size());
  stats.rmse = std::sqrt(sum_squares / n);
  stats.mean = sum / n;
  stats.max = max;
  const std::size_t middle = errors.size() / 2;
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(middle),
                   errors.end());
  stats.median = errors[middle];
  if (errors.size() % 2 == 0) {
    const double below =
        *std::max_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(middle));
    stats.median = 0.5 * (stats.median + below);
  }
  return stats;
}

}  // namespace uampc::evaluator
