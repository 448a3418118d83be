#include "uampc/run_files/csv.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "uampc/run_files/number_format.hpp"

namespace uampc::run_files {

namespace {

std::vector<std::string> splitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    cells.push_back(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    if (comma == std::string::npos) return cells;
    begin = comma + 1;
  }
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : columns_(columns.size()), out_(path) {
  std::string header;
  for (std::size_t i = 0; i < columns.size(); ++i) header += (i ? "," : "") + columns[i];
  out_.write(header + '\n');
}

void CsvWriter::addRow(const std::vector<double>& values) {
  if (values.size() != columns_) {
    throw std::invalid_argument("CSV file " + out_.path() + ": row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_) + " columns");
  }
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) line += (i ? "," : "") + formatDouble(values[i]);
  out_.write(line + '\n');
}

void CsvWriter::close() { out_.close(); }

int CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i);
  }
  return -1;
}

std::size_t CsvTable::requireColumn(const std::string& name) const {
  const int c = column(name);
  if (c < 0) throw std::runtime_error(path + ": no column '" + name + "' in the header");
  return static_cast<std::size_t>(c);
}

double CsvTable::cell(std::size_t row, std::size_t column) const {
  if (column >= rows.at(row).size()) {
    throw std::runtime_error(path + ":" + std::to_string(lines.at(row)) + ": no value for column '" +
                             (column < columns.size() ? columns[column] : std::to_string(column + 1)) + "'");
  }
  return rows[row][column];
}

std::vector<double> CsvTable::values(const std::string& name) const {
  const std::size_t c = requireColumn(name);
  std::vector<double> out;
  out.reserve(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) out.push_back(cell(r, c));
  return out;
}

CsvTable readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read CSV file " + path);
  CsvTable table;
  table.path = path;
  std::string line;
  if (!std::getline(in, line)) return table;
  table.columns = splitCells(line);
  for (int number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::vector<double> row;
    for (const std::string& text : splitCells(line)) {
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0') {
        throw std::runtime_error(path + ":" + std::to_string(number) + ": '" + text + "' is not a number");
      }
      row.push_back(value);
    }
    table.rows.push_back(std::move(row));
    table.lines.push_back(number);
  }
  return table;
}

}  // namespace uampc::run_files
