// Our readers of outside files take a path, not bytes: a fuzz input is written to a file first.
// One directory per fuzzer process under $TMPDIR (or /tmp), removed when the process exits; every
// input overwrites the same file, so a long run leaves nothing behind.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace uampc::fuzz {

class FuzzDirectory {
 public:
  static const std::filesystem::path& path() {
    static FuzzDirectory directory;
    return directory.path_;
  }

 private:
  FuzzDirectory() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/uampc-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a directory like " + pattern);
    path_ = pattern;
  }
  ~FuzzDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::filesystem::path path_;
};

// Writes the input to FuzzDirectory/name and returns that file's path.
inline std::string writeInputFile(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::filesystem::path file = FuzzDirectory::path() / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("cannot write " + file.string());
  return file.string();
}

}  // namespace uampc::fuzz
