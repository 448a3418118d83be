#include "experiment/output_lock.hpp"

#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace uampc::app {

std::optional<FileLock> lockOutputDirectory(const std::string& output_directory, const std::string& command) {
  const std::string path = (fs::path(output_directory) / kOutputLockFile).string();
  LockAttempt attempt = lockFile(path, thisProcess() + " (" + command + ")");
  if (!attempt.held_by.empty()) {
    std::cerr << "uampc experiment: " << output_directory << " is in use by another experiment: " << attempt.held_by
              << "; nothing was done (one experiment at a time on an output directory: wait for it to end, or "
                 "choose another --out)\n";
  } else if (!attempt.error.empty()) {
    std::cerr << "uampc experiment: " << attempt.error << "; nothing was done\n";
  }
  return std::move(attempt.lock);
}

}  // namespace uampc::app
