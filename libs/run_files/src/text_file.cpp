#include "uampc/run_files/text_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace uampc::run_files {

namespace {

// Writes `text` to a new file at `path`; 0, or the errno of the first step that failed. The
// close is checked too: the last buffered bytes reach the file system only there.
int writeNewFile(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return errno;
  int error = std::fwrite(text.data(), 1, text.size(), file) == text.size() ? 0 : errno;
  if (std::fclose(file) != 0 && error == 0) error = errno;
  return error;
}

}  // namespace

std::string cannotWrite(const std::string& path, int error) {
  return "cannot write " + path + ": " + std::strerror(error);
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeTextFile(const std::string& path, const std::string& text) {
  const std::string partial = path + ".partial";
  int error = writeNewFile(partial, text);
  if (error == 0 && std::rename(partial.c_str(), path.c_str()) != 0) error = errno;
  if (error == 0) return;
  std::remove(partial.c_str());  // fails harmlessly when it was never created
  throw std::runtime_error(cannotWrite(path, error));
}

void appendToTextFile(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "ab");
  if (!file) throw std::runtime_error(cannotWrite(path, errno));
  int error = std::fseek(file, 0, SEEK_END) == 0 ? 0 : errno;
  const long size_before = error == 0 ? std::ftell(file) : -1;
  if (error == 0 && size_before < 0) error = errno;
  if (error == 0 && std::fwrite(text.data(), 1, text.size(), file) != text.size()) error = errno;
  if (error == 0 && std::fflush(file) != 0) error = errno;
  // Cut back what reached the file of a write that failed part way (a full disk takes what fits).
  if (error != 0 && size_before >= 0) (void)::ftruncate(fileno(file), size_before);
  if (std::fclose(file) != 0 && error == 0) {
    error = errno;
    (void)::truncate(path.c_str(), size_before);
  }
  if (error != 0) throw std::runtime_error(cannotWrite(path, error));
}

}  // namespace uampc::run_files
