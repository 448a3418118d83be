#include "uampc/run_files/streamed_file.hpp"

#include <cerrno>
#include <stdexcept>

#include "uampc/run_files/text_file.hpp"

namespace uampc::run_files {

StreamedFile::StreamedFile(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw std::runtime_error(cannotWrite(path, errno));
}

StreamedFile::~StreamedFile() {
  if (file_) std::fclose(file_);
}

void StreamedFile::fail(int error) {
  failure_ = cannotWrite(path_, error);
  throw std::runtime_error(failure_);
}

void StreamedFile::write(const std::string& text) {
  if (!failure_.empty()) throw std::runtime_error(failure_);
  if (!file_) throw std::logic_error(path_ + ": written after close");
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) fail(errno);
}

void StreamedFile::close() {
  if (!file_) return;
  const int flushed = std::fflush(file_) == 0 ? 0 : errno;
  const int closed = std::fclose(file_) == 0 ? 0 : errno;
  file_ = nullptr;
  if (!failure_.empty()) throw std::runtime_error(failure_);
  if (flushed != 0 || closed != 0) fail(flushed != 0 ? flushed : closed);
}

}  // namespace uampc::run_files
