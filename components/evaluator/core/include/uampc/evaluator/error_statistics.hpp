// Summary of a set of non-negative errors: RMSE, mean, median, max.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace uampc::evaluator {

struct ErrorStatistics {
  std::size_t count = 0;
  // All NaN when count == 0 (written as null in JSON): an empty run has no error, not zero error.
  double rmse = std::numeric_limits<double>::quiet_NaN();
  double mean = std::numeric_limits<double>::quiet_NaN();
  double median = std::numeric_limits<double>::quiet_NaN();  // mean of the middle two if even
  double max = std::numeric_limits<double>::quiet_NaN();
};

ErrorStatistics summarize(std::vector<double> errors);

}  // namespace uampc::evaluator
