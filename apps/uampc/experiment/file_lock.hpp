// An exclusive lock on a file of an experiment's output directory, for as long as a process
// holds it (the kernel releases it however the process ends): the --out lock of the commands that
// drive an experiment (output_lock.hpp) and the lock of each attempt at a run (run_attempt.hpp).
// Rules: docs/decisions/experiment-output-lock.md.
//
// The file is opened without following a symbolic link (O_NOFOLLOW: a link planted in its place
// could point at any file the user may write, which taking the lock truncates), must be a regular
// file, and is closed on exec (O_CLOEXEC: the runs started meanwhile must not hold it past their
// experiment). The holder writes who it is into it, so that the process refused can name it.
#pragma once

#include <optional>
#include <string>

namespace uampc::app {

struct LockAttempt;

class FileLock {
 public:
  FileLock(FileLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

 private:
  friend LockAttempt lockFile(const std::string& path, const std::string& holder_text);
  explicit FileLock(int fd) : fd_(fd) {}
  int fd_;
};

struct LockAttempt {
  std::optional<FileLock> lock;  // held: the others are empty
  std::string held_by;           // another process holds it: what it wrote ("pid 12 on node3 (...)")
  std::string error;             // it cannot be locked: the file and why (a symbolic link, ...)
};

// Takes the lock on `path` (made if missing, 0644) without waiting, and writes `holder_text` into it.
LockAttempt lockFile(const std::string& path, const std::string& holder_text);

// "pid 1234 on node3": this process, as a lock's holder text begins.
std::string thisProcess();
std::string hostName();

}  // namespace uampc::app
