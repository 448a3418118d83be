#include "uampc/run_files/run_directory.hpp"

#include "uampc/run_files/text_file.hpp"

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
  writeTextFile(inDirectory(run_directory, kDoneMarker), text.str());
}

std::optional<double> readDoneMarker(const std::string& run_directory) {
  const std::string path = inDirectory(run_directory, kDoneMarker);
  if (!fs::is_regular_file(path)) return std::nullopt;
  const std::string text = readTextFile(path);
  const std::size_t at = text.find(kWallTimeKey);
  if (at == std::string::npos) return NAN;
  const char* begin = text.c_str() + at + sizeof(kWallTimeKey) - 1;
  char* end = nullptr;
  const double wall = std::strtod(begin, &end);
  return end == begin ? NAN : wall;
}

void writeFailedMarker(const std::string& run_directory, const std::string& reason) {
  writeTextFile(inDirectory(run_directory, kFailedMarker), reason + "\n");
}

std::string readFailedMarker(const std::string& run_directory) {
  return readTextFile(inDirectory(run_directory, kFailedMarker));
}

}  // namespace uampc::run_files
