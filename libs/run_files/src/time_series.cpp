#include "uampc/run_files/time_series.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "uampc/run_files/run_directory.hpp"

namespace uampc::run_files {

namespace {

// The columns before the samples; the samples' columns are named by uncertaintySampleColumn.
constexpr const char* kUncertaintyColumns[] = {"time", "theta_start", "delta_theta", "command"};
// What stood for all the samples before the file was rectangular (still read).
constexpr char kLegacySamplesColumn[] = "samples...";
constexpr const char* kTimingsColumns[] = {"time", "source", "name", "value"};

template <std::size_t N>
std::string headerLine(const char* const (&columns)[N]) {
  std::string line;
  for (std::size_t i = 0; i < N; ++i) line += (i ? "," : "") + std::string(columns[i]);
  return line;
}

// snprintf into a string: a field of the two files above, in their precision.
template <class... Values>
std::string printed(const char* format, Values... values) {
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof buffer, format, values...);
  if (n < 0) throw std::logic_error(std::string("cannot format ") + format);
  if (static_cast<std::size_t>(n) < sizeof buffer) return std::string(buffer, static_cast<std::size_t>(n));
  std::string text(static_cast<std::size_t>(n) + 1, '\0');
  std::snprintf(text.data(), text.size(), format, values...);
  text.pop_back();
  return text;
}

std::string uncertaintyHeader(std::size_t samples) {
  std::string line = headerLine(kUncertaintyColumns);
  for (std::size_t k = 0; k < samples; ++k) line += "," + uncertaintySampleColumn(k);
  return line;
}

// The header's sample columns: the legacy one (nullopt: rows of any length) or one per sample.
std::optional<std::size_t> sampleColumnsOf(const CsvTable& table) {
  const std::size_t fixed = std::size(kUncertaintyColumns);
  const std::string expected = headerLine(kUncertaintyColumns);
  const auto wrongHeader = [&](const std::string& why) {
    return std::runtime_error(table.path + ":1: not the header of " + kUncertaintyFile + " (" + expected +
                              ",u_000,u_001,...): " + why);
  };
  if (table.columns.size() < fixed) throw wrongHeader("too few columns");
  for (std::size_t i = 0; i < fixed; ++i) {
    if (table.columns[i] != kUncertaintyColumns[i])
      throw wrongHeader("column " + std::to_string(i + 1) + " is '" + table.columns[i] + "'");
  }
  if (table.columns.size() == fixed + 1 && table.columns[fixed] == kLegacySamplesColumn) return std::nullopt;
  for (std::size_t i = fixed; i < table.columns.size(); ++i) {
    if (table.columns[i] != uncertaintySampleColumn(i - fixed))
      throw wrongHeader("column " + std::to_string(i + 1) + " is '" + table.columns[i] + "', expected '" +
                        uncertaintySampleColumn(i - fixed) + "'");
  }
  return table.columns.size() - fixed;
}

}  // namespace

std::string uncertaintySampleColumn(std::size_t k) {
  char name[32];
  std::snprintf(name, sizeof name, "u_%03zu", k);
  return name;
}

UncertaintyWriter::UncertaintyWriter(const std::string& path) : file_(path) {}

UncertaintyWriter::~UncertaintyWriter() {
  try {
    close();
  } catch (const std::exception&) {
    // Said by close() to whoever calls it; a destructor has no one to tell.
  }
}

void UncertaintyWriter::close() {
  if (!samples_) {
    samples_ = 0;
    file_.write(uncertaintyHeader(0) + "\n");
  }
  file_.close();
}

void UncertaintyWriter::add(const UncertaintyRow& row) {
  if (!samples_) {
    samples_ = row.samples.size();
    file_.write(uncertaintyHeader(*samples_) + "\n");
  } else if (row.samples.size() != *samples_) {
    throw std::invalid_argument(file_.path() + ": a row of " + std::to_string(row.samples.size()) +
                                " U samples, but the file's columns hold " + std::to_string(*samples_) +
                                " (its first row's); row left out");
  }
  std::string line = printed("%.9f,%.17g,%.17g,%.17g", row.time, row.theta_start, row.delta_theta, row.command);
  for (double u : row.samples) line += printed(",%.9g", u);
  file_.write(line + "\n");
}

TimingsWriter::TimingsWriter(const std::string& path) : file_(path) { file_.write(headerLine(kTimingsColumns) + "\n"); }

void TimingsWriter::add(const TimingRow& row) {
  file_.write(printed("%.9f,", row.time) + row.source + "," + row.name + printed(",%.9g\n", row.value));
}

std::vector<UncertaintyRow> readUncertainty(const std::string& path) {
  const CsvTable table = readCsv(path);
  if (table.columns.empty()) return {};  // empty: no row was ever written
  const std::optional<std::size_t> samples = sampleColumnsOf(table);
  const std::size_t fixed = std::size(kUncertaintyColumns);
  std::vector<UncertaintyRow> rows;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<double>& v = table.rows[r];
    if (samples && v.size() != table.columns.size()) {
      throw std::runtime_error(path + ":" + std::to_string(table.lines[r]) + ": " + std::to_string(v.size()) +
                               " fields, but the header names " + std::to_string(table.columns.size()));
    }
    if (v.size() < fixed) table.cell(r, fixed - 1);  // throws, naming the line
    UncertaintyRow row{v[0], v[1], v[2], v[3], std::vector<double>(v.begin() + fixed, v.end())};
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<TimingRow> readTimings(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::string line;
  std::getline(in, line);
  if (line != headerLine(kTimingsColumns)) throw std::runtime_error(path + ":1: not the header of " + kTimingsFile);
  std::vector<TimingRow> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::stringstream cells(line);
    TimingRow row;
    std::string time, value;
    if (!std::getline(cells, time, ',') || !std::getline(cells, row.source, ',') ||
        !std::getline(cells, row.name, ',') || !std::getline(cells, value)) {
      throw std::runtime_error(path + ":" + std::to_string(number) + ": expected time,source,name,value");
    }
    char* end = nullptr;
    row.time = std::strtod(time.c_str(), &end);
    const bool time_ok = !time.empty() && *end == '\0';
    row.value = std::strtod(value.c_str(), &end);
    if (!time_ok || value.empty() || *end != '\0') {
      throw std::runtime_error(path + ":" + std::to_string(number) + ": time and value must be numbers");
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace uampc::run_files
