#include "uampc/runtime/domain_run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "uampc/runtime/logger.hpp"

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
  return printableText(text);  // anyone may have written it: a terminal shows it, not obeys it
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw LockFileError("cannot use the lock file " + path + ": " + why);
}

// Closes the descriptor when a check refuses it.
struct FdGuard {
  int fd;
  ~FdGuard() {
    if (fd >= 0) close(fd);
  }
  int release() { return std::exchange(fd, -1); }
};

// The lock directory, opened without following a link. Made 1777 (every user's runs lock in it,
// none can remove another's files) when missing; an existing one is used as it is: the checks on
// its files, not on its owner, are what keep a planted file harmless.
int openDirectory(const std::string& directory) {
  if (mkdir(directory.c_str(), 0700) == 0) {
    if (chmod(directory.c_str(), 01777) != 0) refuse(directory, std::string("chmod 1777: ") + std::strerror(errno));
  } else if (errno != EEXIST) {
    refuse(directory, std::string("cannot create it: ") + std::strerror(errno));
  }
  const int fd = open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    refuse(directory, errno == ELOOP || errno == ENOTDIR
                          ? "it is not a directory (a link or a file); remove it, or ask whoever made it"
                          : std::string("cannot open it: ") + std::strerror(errno));
  }
  return fd;
}

// Opens `name` in the directory, never through a link and never blocking (a planted FIFO): an
// existing file first, read-write when this user may write it, else read-only (flock works on
// either); a new one with O_EXCL, mode 0644 (others read who holds it, only its maker writes it).
// Opening before creating matters: with fs.protected_regular, O_CREAT on another user's file in a
// sticky directory fails even where a plain open works.
int openLockFile(int directory_fd, const std::string& name, const std::string& path) {
  constexpr int kFlags = O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY;
  for (int attempt = 0; attempt < 3; ++attempt) {
    int fd = openat(directory_fd, name.c_str(), O_RDWR | kFlags);
    if (fd < 0 && (errno == EACCES || errno == EPERM)) fd = openat(directory_fd, name.c_str(), O_RDONLY | kFlags);
    if (fd >= 0) return fd;
    if (errno == ELOOP) refuse(path, "it is a symbolic link (someone planted it?); remove it");
    if (errno != ENOENT) refuse(path, std::strerror(errno));
    fd = openat(directory_fd, name.c_str(), O_RDWR | O_CREAT | O_EXCL | kFlags, 0644);
    if (fd >= 0) return fd;
    if (errno != EEXIST) refuse(path, std::string("cannot create it: ") + std::strerror(errno));
    // Another launch made it between the two opens: open it again as an existing file.
  }
  refuse(path, "it keeps appearing and vanishing");
}

}  // namespace

std::string DomainRunLock::fileNameFor(int domain_id) { return "run-on-domain-" + std::to_string(domain_id) + ".lock"; }

std::string DomainRunLock::pathFor(int domain_id) { return std::string(kDirectory) + "/" + fileNameFor(domain_id); }

std::optional<DomainRunLock> DomainRunLock::take(int domain_id, const std::string& description, std::string* holder) {
  return takeFile(kDirectory, fileNameFor(domain_id), description, holder);
}

std::optional<DomainRunLock> DomainRunLock::takeFile(const std::string& directory, const std::string& name,
                                                     const std::string& description, std::string* holder) {
  const std::string path = directory + "/" + name;
  FdGuard dir{openDirectory(directory)};
  FdGuard file{openLockFile(dir.fd, name, path)};
  struct stat st {};
  if (fstat(file.fd, &st) != 0) refuse(path, std::strerror(errno));
  if (!S_ISREG(st.st_mode)) refuse(path, "it is not a regular file; remove it");
  // A hard link to another file (a user's own, or root's where hard links are not protected)
  // would have this launch write into that file.
  if (st.st_nlink != 1) refuse(path, "it has " + std::to_string(st.st_nlink) + " hard links; remove it");
  if (flock(file.fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK) refuse(path, std::string("flock: ") + std::strerror(errno));
    if (holder) *holder = readAll(file.fd);
    return std::nullopt;
  }
  // The description only into a file this user made: never truncate or write anyone else's.
  const bool ours = st.st_uid == geteuid();
  if (ours && !description.empty() && ftruncate(file.fd, 0) == 0) {
    const std::string text = description + "\n";
    (void)!pwrite(file.fd, text.data(), text.size(), 0);
  }
  return DomainRunLock(file.release());
}

DomainRunLock::~DomainRunLock() {
  if (fd_ >= 0) close(fd_);
}

}  // namespace uampc
