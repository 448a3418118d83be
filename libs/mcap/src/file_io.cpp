#include "file_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::detail {

namespace {

// Bytes handed to the C library at once: chunks go straight through, small records are gathered.
constexpr std::size_t kWriteBuffer = 1 << 20;

std::string systemError() { return std::strerror(errno); }

}  // namespace

std::string recordError(const std::string& path, std::uint64_t offset, const std::string& what) {
  return path + ": record at byte " + std::to_string(offset) + ": " + what;
}

OutputFile::OutputFile(const std::string& path) : path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) fail("cannot create: " + systemError());
  std::setvbuf(file_, nullptr, _IOFBF, kWriteBuffer);
}

OutputFile::~OutputFile() {
  if (file_) std::fclose(file_);
}

void OutputFile::fail(const std::string& what) const { throw McapError(path_ + ": " + what); }

void OutputFile::write(const void* data, std::size_t size) {
  if (!file_) fail("write after close");
  if (size > 0 && std::fwrite(data, 1, size, file_) != size) fail("cannot write: " + systemError());
  written_ += size;
}

void OutputFile::flush() {
  if (file_ && std::fflush(file_) != 0) fail("cannot write: " + systemError());
}

void OutputFile::close() {
  if (!file_) return;
  const bool flushed = std::fflush(file_) == 0;
  const std::string flush_error = flushed ? "" : systemError();
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed) fail("cannot write: " + flush_error);
  if (!closed) fail("cannot close: " + systemError());
}

InputFile::InputFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw McapError(path + ": cannot open: " + systemError());
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw McapError(path + ": not a regular file");
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

Buffer InputFile::read(std::uint64_t offset, std::uint64_t size) const {
  Buffer out;
  read(offset, size, out);
  return out;
}

void InputFile::read(std::uint64_t offset, std::uint64_t size, Buffer& out) const {
  if (offset > size_ || size > size_ - offset) {
    throw McapError(recordError(
        path_, offset,
        "reading " + std::to_string(size) + " bytes runs past the end of the " + std::to_string(size_) + "-byte file"));
  }
  out.resize(static_cast<std::size_t>(size));
  std::uint64_t done = 0;
  while (done < size) {
    const ssize_t n =
        ::pread(fd_, out.data() + done, static_cast<std::size_t>(size - done), static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw McapError(path_ + ": cannot read: " + systemError());
    if (n == 0) throw McapError(recordError(path_, offset + done, "the file ends early (did it shrink?)"));
    done += static_cast<std::uint64_t>(n);
  }
}

}  // namespace uampc::mcap::detail
