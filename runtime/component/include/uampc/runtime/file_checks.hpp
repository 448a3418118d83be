// std::filesystem's checks without their exception, for paths that come from users (a scene, a
// command line, an experiment). The system refuses to look some names up at all: a name longer
// than 255 bytes, a component that is a file, a directory without search permission. The throwing
// overloads then end validation with an uncaught filesystem_error (fuzz_scene_yaml found a
// 600-byte trajectory_file that aborted `uampc validate`); these answer false, and the caller
// reports the path as it reports a missing file, by name and line.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

namespace uampc {

inline bool pathExists(const std::filesystem::path& path) {
  std::error_code ignored;
  return std::filesystem::exists(path, ignored);
}

inline bool isRegularFile(const std::filesystem::path& path) {
  std::error_code ignored;
  return std::filesystem::is_regular_file(path, ignored);
}

inline bool isDirectory(const std::filesystem::path& path) {
  std::error_code ignored;
  return std::filesystem::is_directory(path, ignored);
}

// Why a path a user gave as a file is not one: "is a directory, not a file", "is not a regular
// file" (a device, a pipe), or "file not found"; for messages.
inline std::string whyNotAFile(const std::filesystem::path& path) {
  if (isDirectory(path)) return "is a directory, not a file";
  if (pathExists(path)) return "is not a regular file";
  return "file not found";
}

}  // namespace uampc
