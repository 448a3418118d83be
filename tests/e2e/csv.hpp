// Reading the CSV files test components write.
#pragma once

#include <string>
#include <vector>

namespace uampc::test {

// Rows of numbers; the header line is skipped.
std::vector<std::vector<double>> readCsv(const std::string& path);

}  // namespace uampc::test
