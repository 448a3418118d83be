#include "uampc/run_files/run_directory.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace uampc::run_files {

namespace {

constexpr char kPanoramaPrefix[] = "panorama_";
constexpr char kPanoramaSuffix[] = ".png";
constexpr char kWallTimeKey[] = "wall_time_s=";

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

std::string panoramaSnapshotName(double sim_time_s) {
  char name[64];
  std::snprintf(name, sizeof(name), "%s%07.1f%s", kPanoramaPrefix, sim_time_s, kPanoramaSuffix);
  return name;
}

std::optional<std::string> panoramaSnapshotTime(const std::string& file_name) {
  const std::string prefix = kPanoramaPrefix, suffix = kPanoramaSuffix;
  if (file_name.size() <= prefix.size() + suffix.size() || file_name.compare(0, prefix.size(), prefix) != 0 ||
      file_name.compare(file_name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  return file_name.substr(prefix.size(), file_name.size() - prefix.size() - suffix.size());
}

std::string inDirectory(const std::string& directory, const std::string& name) {
  return (fs::path(directory) / name).string();
}

void writeDoneMarker(const std::string& run_directory, double wall_time_s) {
  std::ostringstream text;
  text << kWallTimeKey << wall_time_s << "\n";
  writeText(inDirectory(run_directory, kDoneMarker), text.str());
}

std::optional<double> readDoneMarker(const std::string& run_directory) {
  const std::string path = inDirectory(run_directory, kDoneMarker);
  if (!fs::is_regular_file(path)) return std::nullopt;
  const std::string text = readText(path);
  const std::size_t at = text.find(kWallTimeKey);
  if (at == std::string::npos) return NAN;
  const char* begin = text.c_str() + at + sizeof(kWallTimeKey) - 1;
  char* end = nullptr;
  const double wall = std::strtod(begin, &end);
  return end == begin ? NAN : wall;
}

void writeFailedMarker(const std::string& run_directory, const std::string& reason) {
  writeText(inDirectory(run_directory, kFailedMarker), reason + "\n");
}

std::string readFailedMarker(const std::string& run_directory) {
  return readText(inDirectory(run_directory, kFailedMarker));
}

}  // namespace uampc::run_files
