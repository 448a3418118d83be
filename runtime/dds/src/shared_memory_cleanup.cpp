#include "uampc/runtime/shared_memory_cleanup.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <regex>
#include <vector>

namespace uampc {

namespace {

// Whether some live process holds the lock file (Fast DDS's owner of the segment does).
bool lockedByAnother(const std::string& lock_file) {
  const int fd = open(lock_file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return true;  // gone or unreadable: not ours to judge
  const bool free = flock(fd, LOCK_EX | LOCK_NB) == 0;
  close(fd);  // also releases the lock just taken
  return !free;
}

}  // namespace

int removeAbandonedSharedMemorySegments(const std::string& directory) {
  static const std::regex kSegmentLock("fastrtps_[0-9a-z]{16}_el");
  namespace fs = std::filesystem;
  std::vector<fs::path> lock_files;  // listed first: removing while iterating is unspecified
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    if (std::regex_match(it->path().filename().string(), kSegmentLock)) lock_files.push_back(it->path());
  }
  int removed = 0;
  for (const auto& lock_file : lock_files) {
    if (lockedByAnother(lock_file.string())) continue;
    std::error_code ignored;
    const std::string lock_name = lock_file.filename().string();
    fs::remove(lock_file.parent_path() / lock_name.substr(0, lock_name.size() - 3), ignored);
    if (fs::remove(lock_file, ignored)) ++removed;
  }
  return removed;
}

}  // namespace uampc
