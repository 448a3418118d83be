#include "experiment/file_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace uampc::app {

namespace {

constexpr std::size_t kMostHolderText = 4096;

std::string holderTextOf(int fd) {
  std::string text;
  char buffer[512];
  ssize_t n = 0;
  while (text.size() < kMostHolderText && (n = pread(fd, buffer, sizeof buffer, static_cast<off_t>(text.size()))) > 0) {
    text.append(buffer, static_cast<std::size_t>(n));
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  // Written by the holder just after it took the lock: empty in between.
  return text.empty() ? "another process (it has not said which yet)" : text;
}

std::string openError(const std::string& path, int error) {
  if (error == ELOOP) return "cannot lock " + path + ": it is a symbolic link, not a lock file of its own";
  return "cannot lock " + path + ": " + std::strerror(error);
}

}  // namespace

FileLock& FileLock::operator=(FileLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
  }
  return *this;
}

FileLock::~FileLock() {
  if (fd_ >= 0) close(fd_);
}

LockAttempt lockFile(const std::string& path, const std::string& holder_text) {
  LockAttempt attempt;
  // O_NONBLOCK: a FIFO in its place must not hang the open (it is then refused as not regular).
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY | O_NONBLOCK, 0644);
  if (fd < 0) {
    attempt.error = openError(path, errno);
    return attempt;
  }
  FileLock lock(fd);
  struct stat status {};
  if (fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) {
    attempt.error = "cannot lock " + path + ": it is not a regular file";
    return attempt;
  }
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EWOULDBLOCK)
      attempt.held_by = holderTextOf(fd);
    else
      attempt.error = "cannot lock " + path + ": " + std::strerror(errno);
    return attempt;
  }
  // Held whether or not the text is written: without it, a refused process cannot name the holder.
  const std::string text = holder_text + "\n";
  (void)!(ftruncate(fd, 0) == 0 && pwrite(fd, text.data(), text.size(), 0) > 0);
  attempt.lock.emplace(std::move(lock));
  return attempt;
}

std::string hostName() {
  char name[256] = {};
  gethostname(name, sizeof(name) - 1);
  return name;
}

std::string thisProcess() { return "pid " + std::to_string(getpid()) + " on " + hostName(); }

}  // namespace uampc::app
