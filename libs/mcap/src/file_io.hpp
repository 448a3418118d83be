// The file under an MCAP writer or reader. Every failure is an McapError naming the file.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "byte_io.hpp"

namespace uampc::mcap::detail {

// "FILE: record at byte OFFSET: WHAT": how the reader names a bad record.
std::string recordError(const std::string& path, std::uint64_t offset, const std::string& what);

// Appends to a new file (truncating an existing one).
class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(const void* data, std::size_t size);
  void write(const Bytes& bytes) { write(bytes.data(), bytes.size()); }
  // Hands what is buffered to the kernel: after it, a process killed with SIGKILL leaves the bytes
  // written so far in the file.
  void flush();
  void close();  // flushes; idempotent
  std::uint64_t bytesWritten() const { return written_; }
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what) const;

  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t written_ = 0;
};

// Random access to a file that is read only.
class InputFile {
 public:
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  std::uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }
  // The `size` bytes at `offset`; the caller checks that they lie inside the file (an McapError if
  // they do not: the file shrank while being read).
  Buffer read(std::uint64_t offset, std::uint64_t size) const;
  // The same into `out`, whose capacity is reused.
  void read(std::uint64_t offset, std::uint64_t size, Buffer& out) const;

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

}  // namespace uampc::mcap::detail
