#include "uampc/run_files/time_series.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "uampc/run_files/run_directory.hpp"

namespace uampc::run_files {

namespace {

// The columns before the samples, and the name standing for the samples.
constexpr const char* kUncertaintyColumns[] = {"time", "theta_start", "delta_theta", "command"};
constexpr char kSamplesColumn[] = "samples...";
constexpr const char* kTimingsColumns[] = {"time", "source", "name", "value"};

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

template <std::size_t N>
std::string headerLine(const char* const (&columns)[N], const char* last = nullptr) {
  std::string line;
  for (std::size_t i = 0; i < N; ++i) line += (i ? "," : "") + std::string(columns[i]);
  if (last) line += std::string(",") + last;
  return line;
}

File openForWriting(const std::string& path, const std::string& header) {
  File file(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!file) throw std::runtime_error("cannot write " + path);
  std::fputs((header + "\n").c_str(), file.get());
  return file;
}

}  // namespace

UncertaintyWriter::UncertaintyWriter(const std::string& path)
    : file_(openForWriting(path, headerLine(kUncertaintyColumns, kSamplesColumn))) {}

void UncertaintyWriter::add(const UncertaintyRow& row) {
  std::fprintf(file_.get(), "%.9f,%.17g,%.17g,%.17g", row.time, row.theta_start, row.delta_theta, row.command);
  for (double u : row.samples) std::fprintf(file_.get(), ",%.9g", u);
  std::fputc('\n', file_.get());
}

TimingsWriter::TimingsWriter(const std::string& path) : file_(openForWriting(path, headerLine(kTimingsColumns))) {}

void TimingsWriter::add(const TimingRow& row) {
  std::fprintf(file_.get(), "%.9f,%s,%s,%.9g\n", row.time, row.source.c_str(), row.name.c_str(), row.value);
}

std::vector<UncertaintyRow> readUncertainty(const std::string& path) {
  const CsvTable table = readCsv(path);
  const std::size_t fixed = std::size(kUncertaintyColumns);
  for (std::size_t i = 0; i < fixed; ++i) table.requireColumn(kUncertaintyColumns[i]);
  std::vector<UncertaintyRow> rows;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const std::vector<double>& v = table.rows[r];
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
