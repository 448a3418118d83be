#include "uampc/runtime/domain_run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace uampc {

namespace {

std::string readAll(int fd) {
  std::string text;
  char buffer[512];
  ssize_t n = 0;
  off_t at = 0;
  while ((n = pread(fd, buffer, sizeof buffer, at)) > 0 && text.size() < 4096) {
    text.append(buffer, static_cast<std::size_t>(n));
    at += n;
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  return text;
}

}  // namespace

std::string DomainRunLock::pathFor(int domain_id) {
  return "/tmp/uampc-run-on-domain-" + std::to_string(domain_id) + ".lock";
}

std::optional<DomainRunLock> DomainRunLock::take(int domain_id, const std::string& description, std::string* holder) {
  return takeFile(pathFor(domain_id), description, holder);
}

std::optional<DomainRunLock> DomainRunLock::takeFile(const std::string& path, const std::string& description,
                                                     std::string* holder) {
  // Read-write to leave a description; read-only when another user made the file (flock works on
  // either). CLOEXEC: the run's processes must not hold the lock past the launcher.
  int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  const bool writable = fd >= 0;
  if (fd < 0) fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return DomainRunLock(-1);  // no /tmp to lock in: nothing to coordinate with
  if (writable) fchmod(fd, 0666);        // other users' runs lock the same file
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (holder) *holder = readAll(fd);
    close(fd);
    return std::nullopt;
  }
  if (writable && !description.empty() && ftruncate(fd, 0) == 0) {
    const std::string text = description + "\n";
    (void)!pwrite(fd, text.data(), text.size(), 0);
  }
  return DomainRunLock(fd);
}

DomainRunLock::~DomainRunLock() {
  if (fd_ >= 0) close(fd_);
}

}  // namespace uampc
