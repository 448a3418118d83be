#include "csv.hpp"

#include <sstream>

#include "command_runner.hpp"

namespace uampc::test {

std::vector<std::vector<double>> readCsv(const std::string& path) {
  std::stringstream in(readFile(path));
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace uampc::test
