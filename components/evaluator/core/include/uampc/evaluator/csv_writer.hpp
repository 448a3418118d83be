// CSV files of numbers, for time series (ATE over time, voxels per window).
#pragma once

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

namespace uampc::evaluator {

class CsvWriter {
 public:
  // Creates path and writes the header line; throws std::runtime_error naming path on failure.
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);

  // One row, as many values as columns (else std::invalid_argument). Doubles shortest
  // round-trip; NaN written as "nan", infinities as "inf" / "-inf" (what numpy and pandas read).
  void addRow(const std::vector<double>& values);

  // Flushes; throws std::runtime_error naming path if anything failed to write.
  void close();

 private:
  std::string path_;
  std::size_t columns_;
  std::ofstream out_;
};

// Shortest text that reads back as the same double ("nan", "inf", "-inf" for those).
std::string formatDouble(double value);

}  // namespace uampc::evaluator
