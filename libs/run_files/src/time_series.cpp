#include "uampc/run_files/time_series.hpp"

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

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

template <std::size_t N>
std::string headerLine(const char* const (&columns)[N]) {
  std::string line;
  for (std::size_t i = 0; i < N; ++i) line += (i ? "," : "") + std::string(columns[i]);
  return line;
}

File openForWriting(const std::string& path) {
  File file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write " + path);
  return file;
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

UncertaintyWriter::UncertaintyWriter(const std::string& path) : path_(path), file_(openForWriting(path)) {}

UncertaintyWriter::~UncertaintyWriter() {
  if (file_ && !samples_) std::fputs((uncertaintyHeader(0) + "\n").c_str(), file_.get());
}

void UncertaintyWriter::add(const UncertaintyRow& row) {
  if (!samples_) {
    samples_ = row.samples.size();
    std::fputs((uncertaintyHeader(*samples_) + "\n").c_str(), file_.get());
  } else if (row.samples.size() != *samples_) {
    throw std::invalid_argument(path_ + ": a row of " + std::to_string(row.samples.size()) +
                                " U samples, but the file's columns hold " + std::to_string(*samples_) +
                                " (its first row's); row left out");
  }
  std::fprintf(file_.get(), "%.9f,%.17g,%.17g,%.17g", row.time, row.theta_start, row.delta_theta, row.command);
  for (double u : row.samples) std::fprintf(file_.get(), ",%.9g", u);
  std::fputc('\n', file_.get());
}

TimingsWriter::TimingsWriter(const std::string& path) : file_(openForWriting(path)) {
  std::fputs((headerLine(kTimingsColumns) + "\n").c_str(), file_.get());
}

void TimingsWriter::add(const TimingRow& row) {
  std::fprintf(file_.get(), "%.9f,%s,%s,%.9g\n", row.time, row.source.c_str(), row.name.c_str(), row.value);
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
