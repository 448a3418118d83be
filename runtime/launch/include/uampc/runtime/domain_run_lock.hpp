// One run per DDS domain on a host. Two runs on one domain hear each other's clock and topics;
// each `uampc launch` holds an exclusive lock on /tmp/uampc-run-on-domain-D.lock for as long as it
// runs (the kernel releases it however the launcher ends), and a second launch on the domain is
// refused before it starts anything, so that the run already there goes on untouched
// (docs/decisions/one-run-per-domain.md). Runs on other hosts sharing a domain are not seen by a
// lock; the lockstep protocol's own checks catch those (docs/dev/time-and-lockstep.md).
#pragma once

#include <optional>
#include <string>

namespace uampc {

class DomainRunLock {
 public:
  // Takes the domain's lock and writes `description` (what this run is) into its file. When
  // another run holds it: nullopt, and `holder` says what that run wrote.
  static std::optional<DomainRunLock> take(int domain_id, const std::string& description, std::string* holder);
  // The same on any lock file of the host (the experiment's tasks claim their domains with one).
  static std::optional<DomainRunLock> takeFile(const std::string& path, const std::string& description,
                                               std::string* holder);

  DomainRunLock(DomainRunLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  DomainRunLock(const DomainRunLock&) = delete;
  DomainRunLock& operator=(const DomainRunLock&) = delete;
  DomainRunLock& operator=(DomainRunLock&&) = delete;
  ~DomainRunLock();

  static std::string pathFor(int domain_id);

 private:
  explicit DomainRunLock(int fd) : fd_(fd) {}
  int fd_;
};

}  // namespace uampc
