// One run per DDS domain on a host. Two runs on one domain hear each other's clock and topics;
// each `uampc launch` holds an exclusive lock on /tmp/uampc/run-on-domain-D.lock for as long as it
// runs (the kernel releases it however the launcher ends), and a second launch on the domain is
// refused before it starts anything, so that the run already there goes on untouched
// (docs/decisions/one-run-per-domain.md). Runs on other hosts sharing a domain are not seen by a
// lock; the lockstep protocol's own checks catch those (docs/dev/time-and-lockstep.md).
//
// The lock directory is shared by every user of the host, so a file in it may have been planted by
// anyone: a lock file is never followed as a link, must be a regular file with one link, and is
// written (its description) only when this user made it (docs/decisions/lock-files-never-followed.md).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace uampc {

// A lock file that cannot be used safely (a link, not a regular file, no lock directory ...):
// the message names the path and says why; the command refuses to start.
class LockFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class DomainRunLock {
 public:
  // The host's lock directory, shared by every user (sticky, like /tmp): /tmp/uampc.
  static constexpr const char* kDirectory = "/tmp/uampc";

  // Takes the domain's lock and writes `description` (what this run is) into its file. When
  // another run holds it: nullopt, and `holder` says what that run wrote (control bytes escaped).
  // Throws LockFileError when the lock cannot be taken safely.
  static std::optional<DomainRunLock> take(int domain_id, const std::string& description, std::string* holder);
  // The same on any lock file `name` of the directory `directory` (the experiment's tasks claim
  // their domains with one; tests use a directory of their own). The directory is created, mode
  // 1777, when missing.
  static std::optional<DomainRunLock> takeFile(const std::string& directory, const std::string& name,
                                               const std::string& description, std::string* holder);

  DomainRunLock(DomainRunLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  DomainRunLock(const DomainRunLock&) = delete;
  DomainRunLock& operator=(const DomainRunLock&) = delete;
  DomainRunLock& operator=(DomainRunLock&&) = delete;
  ~DomainRunLock();

  static std::string fileNameFor(int domain_id);
  static std::string pathFor(int domain_id);

 private:
  explicit DomainRunLock(int fd) : fd_(fd) {}
  int fd_;
};

}  // namespace uampc
