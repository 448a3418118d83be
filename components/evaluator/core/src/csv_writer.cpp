#include "uampc/evaluator/csv_writer.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace uampc::evaluator {

std::string formatDouble(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (error != std::errc()) throw std::runtime_error("formatDouble: cannot format a double");
  return std::string(buffer, end);
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), columns_(columns.size()), out_(path) {
  if (!out_) throw std::runtime_error("cannot open CSV file " + path + " for writing");
  for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
  out_ << '\n';
}

void CsvWriter::addRow(const std::vector<double>& values) {
  if (values.size() != columns_) {
    throw std::invalid_argument("CSV file " + path_ + ": row of " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_) + " columns");
  }
  for (std::size_t i = 0; i < values.size(); ++i) out_ << (i ? "," : "") << formatDouble(values[i]);
  out_ << '\n';
}

void CsvWriter::close() {
  out_.flush();
  if (!out_) throw std::runtime_error("error writing CSV file " + path_);
  out_.close();
}

}  // namespace uampc::evaluator
