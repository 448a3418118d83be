// The emulated servo's end of the wire: a pseudo-terminal whose slave the host opens through a
// symlink, as it opens /dev/serial/by-id/... for a real USB adapter.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uampc::dynamixel::emulation {

class PseudoTerminal {
 public:
  // openpty, the slave in raw mode, `link` -> the slave. Throws std::runtime_error. A stale
  // symlink at `link` is replaced; anything else there is refused.
  explicit PseudoTerminal(std::string link);
  // Closes both ends (the host's open slave hangs up) and removes the link if it still points here.
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  const std::string& slavePath() const { return slave_path_; }
  bool waitReadable(std::chrono::milliseconds timeout) const;
  // What the host wrote, up to `size` bytes without blocking; 0 when nothing is waiting.
  std::size_t readSome(std::uint8_t* buffer, std::size_t size);
  // Writes without blocking; returns how many bytes went out (fewer when nobody reads the slave).
  std::size_t writeSome(const std::vector<std::uint8_t>& bytes);

 private:
  std::string link_;
  std::string slave_path_;
  int master_ = -1;
  // Held open so that the master never sees a hang-up while the host has the port closed.
  int slave_ = -1;
};

}  // namespace uampc::dynamixel::emulation
