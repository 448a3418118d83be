// A full disk for tests that must not need root or a mount: the file size limit (RLIMIT_FSIZE)
// with SIGXFSZ ignored. A write that would grow a regular file beyond the limit then fails with
// EFBIG (a write that crosses it is cut short first, as on a disk that fills up), through the
// same write(2) -> fwrite/fflush/fclose/ofstream failures a full disk gives with ENOSPC; only the
// reason differs ("File too large" instead of "No space left on device"). It touches regular files
// only (pipes, and so the test's view of the output, are unaffected), and a child process inherits
// both the limit and the ignored signal, as the processes of a run and of an experiment do.
// Fast DDS cannot map its shared-memory segments beyond the limit (it says so, and talks UDP).
// Streaming writers can also be pointed at /dev/full, where every write fails with ENOSPC.
#pragma once

#include <signal.h>
#include <sys/resource.h>

#include <cstddef>
#include <stdexcept>
#include <string>

namespace uampc::test {

// `command` for runShell with its files limited to `bytes` (rounded down to dash's ulimit unit,
// 512-byte blocks).
inline std::string withFileSizeLimit(std::size_t bytes, const std::string& command) {
  return "trap '' XFSZ; ulimit -f " + std::to_string(bytes / 512) + "; " + command;
}

// The same in this process, for the scope of the object (unit tests of the writers).
class ScopedFileSizeLimit {
 public:
  explicit ScopedFileSizeLimit(rlim_t bytes) {
    if (getrlimit(RLIMIT_FSIZE, &before_) != 0) throw std::runtime_error("getrlimit failed");
    previous_handler_ = signal(SIGXFSZ, SIG_IGN);
    rlimit limit = before_;
    limit.rlim_cur = bytes;
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) throw std::runtime_error("setrlimit failed");
  }
  ~ScopedFileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &before_);
    signal(SIGXFSZ, previous_handler_);
  }
  ScopedFileSizeLimit(const ScopedFileSizeLimit&) = delete;
  ScopedFileSizeLimit& operator=(const ScopedFileSizeLimit&) = delete;

 private:
  rlimit before_{};
  sighandler_t previous_handler_ = SIG_DFL;
};

}  // namespace uampc::test
