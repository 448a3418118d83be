#include "pseudo_terminal.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace uampc::dynamixel::emulation {
namespace {

std::runtime_error systemError(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

void closeOnExec(int fd) { ::fcntl(fd, F_SETFD, ::fcntl(fd, F_GETFD) | FD_CLOEXEC); }

std::string readLink(const std::string& link) {
  std::array<char, 4096> target{};
  const ssize_t size = ::readlink(link.c_str(), target.data(), target.size() - 1);
  return size < 0 ? std::string() : std::string(target.data(), static_cast<std::size_t>(size));
}

// A new symlink under a temporary name renamed over the link: the host never sees it missing
// or half made.
void createLink(const std::string& link, const std::string& target) {
  struct stat existing {};
  if (::lstat(link.c_str(), &existing) == 0 && !S_ISLNK(existing.st_mode)) {
    throw std::runtime_error(link + " exists and is not a symlink; not replacing it");
  }
  static std::atomic<int> counter{0};
  const std::string temporary = link + ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  if (::symlink(target.c_str(), temporary.c_str()) != 0) throw systemError("cannot create the link " + link);
  if (::rename(temporary.c_str(), link.c_str()) != 0) {
    const std::runtime_error error = systemError("cannot create the link " + link);
    ::unlink(temporary.c_str());
    throw error;
  }
}

}  // namespace

PseudoTerminal::PseudoTerminal(std::string link) : link_(std::move(link)) {
  if (::openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) throw systemError("openpty");
  try {
    closeOnExec(master_);
    closeOnExec(slave_);
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
    termios raw{};
    if (::tcgetattr(slave_, &raw) != 0) throw systemError("tcgetattr");
    ::cfmakeraw(&raw);  // no echo, no line editing, no CR/LF translation: bytes as a UART carries them
    if (::tcsetattr(slave_, TCSANOW, &raw) != 0) throw systemError("tcsetattr");
    std::array<char, 128> name{};
    if (::ptsname_r(master_, name.data(), name.size()) != 0) throw systemError("ptsname");
    slave_path_ = name.data();
    createLink(link_, slave_path_);
  } catch (...) {
    ::close(master_);
    ::close(slave_);
    throw;
  }
}

PseudoTerminal::~PseudoTerminal() {
  // Not another emulator's link that replaced ours.
  if (readLink(link_) == slave_path_) ::unlink(link_.c_str());
  ::close(master_);
  ::close(slave_);
}

bool PseudoTerminal::waitReadable(std::chrono::milliseconds timeout) const {
  pollfd fd{master_, POLLIN, 0};
  const int ready = ::poll(&fd, 1, static_cast<int>(timeout.count()));
  if (ready > 0 && !(fd.revents & POLLIN)) {
    // A hang-up or error, which the held slave should prevent: wait anyway rather than spin.
    std::this_thread::sleep_for(timeout);
  }
  return ready > 0 && (fd.revents & POLLIN);
}

std::size_t PseudoTerminal::readSome(std::uint8_t* buffer, std::size_t size) {
  const ssize_t n = ::read(master_, buffer, size);
  return n > 0 ? static_cast<std::size_t>(n) : 0;
}

std::size_t PseudoTerminal::writeSome(const std::vector<std::uint8_t>& bytes) {
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(master_, bytes.data() + written, bytes.size() - written);
    if (n > 0) {
      written += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EAGAIN: the host does not read; what a UART would lose too
    }
  }
  return written;
}

}  // namespace uampc::dynamixel::emulation
