// CSV files of numbers with a header line: the one writer and the one reader of the repository.
// Typed rows (time_series.hpp) name their columns once, in a fields() function both use.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "uampc/run_files/streamed_file.hpp"

namespace uampc::run_files {

class CsvWriter {
 public:
  // Creates path and writes the header line. A write that fails throws std::runtime_error
  // "cannot write PATH: REASON", here, in addRow or in close (streamed_file.hpp).
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);

  // One row, as many values as columns (else std::invalid_argument). Doubles shortest
  // round-trip; NaN written as "nan", infinities as "inf" / "-inf".
  void addRow(const std::vector<double>& values);

  // Flushes and closes; throws as above if anything failed to write.
  void close();

 private:
  std::size_t columns_;
  StreamedFile out_;
};

// A CSV file read back: the header's names and numeric rows. Rows may differ in length (as in
// uncertainty.csv files written before it was rectangular: their last header name stood for all
// the samples); readers that need a rectangular table check it.
struct CsvTable {
  std::string path;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;                     // each row's line number in the file, for messages
  int column(const std::string& name) const;  // -1 if absent
  // These throw std::runtime_error naming the file (and line) when the column is absent or a row
  // is too short to hold it.
  std::size_t requireColumn(const std::string& name) const;
  double cell(std::size_t row, std::size_t column) const;
  std::vector<double> values(const std::string& name) const;
};

// Every cell must be a number ("nan", "inf" included); blank lines are skipped. Throws
// std::runtime_error naming path when the file cannot be read, or path:line and the cell when a
// cell is not a number.
CsvTable readCsv(const std::string& path);

// ---------------------------------------------------------------- typed rows
// A row type lists its columns once, in order, for writing and reading alike:
//   struct AteRow { double time, ate_m;
//     template <class Row, class Visit> static void fields(Row& row, Visit&& visit) {
//       visit("time", row.time); visit("ate_m", row.ate_m); } };
// Fields are arithmetic (double, integers, bool), written as doubles.

template <class Row>
std::vector<std::string> columnsOf() {
  std::vector<std::string> columns;
  Row row{};
  Row::fields(row, [&columns](const char* name, auto&) { columns.push_back(name); });
  return columns;
}

template <class Row>
std::vector<double> valuesOf(const Row& row) {
  std::vector<double> values;
  Row::fields(row, [&values](const char*, const auto& value) { values.push_back(static_cast<double>(value)); });
  return values;
}

// Writes rows of one type as they come (a file that grows through a run).
template <class Row>
class RowWriter {
 public:
  explicit RowWriter(const std::string& path) : csv_(path, columnsOf<Row>()) {}
  void add(const Row& row) { csv_.addRow(valuesOf(row)); }
  void close() { csv_.close(); }

 private:
  CsvWriter csv_;
};

template <class Row>
void writeRows(const std::string& path, const std::vector<Row>& rows) {
  RowWriter<Row> writer(path);
  for (const Row& row : rows) writer.add(row);
  writer.close();
}

// Reads the columns by name (their order in the file does not matter); throws as readCsv and
// CsvTable::cell do.
template <class Row>
std::vector<Row> readRows(const std::string& path) {
  const CsvTable table = readCsv(path);
  std::vector<std::size_t> index;
  for (const std::string& name : columnsOf<Row>()) index.push_back(table.requireColumn(name));
  std::vector<Row> rows;
  rows.reserve(table.rows.size());
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    Row row{};
    std::size_t k = 0;
    Row::fields(row, [&](const char*, auto& field) {
      using Field = std::remove_reference_t<decltype(field)>;
      const double value = table.cell(r, index[k++]);
      if constexpr (std::is_same_v<Field, bool>)
        field = value != 0.0;
      else
        field = static_cast<Field>(value);
    });
    rows.push_back(row);
  }
  return rows;
}

}  // namespace uampc::run_files
