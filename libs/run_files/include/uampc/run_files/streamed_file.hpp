// A file written piece by piece through a run (motor.csv, timings.csv, uncertainty.csv): the one
// place their writes are checked. A write that fails (a full disk, a file size limit) throws
// "cannot write PATH: REASON", and so does every write after it: a file cut short must not go on
// with rows from after a gap. What reached the file stays; the run that wrote it fails
// (docs/decisions/run-files-whole-or-absent.md).
#pragma once

#include <cstdio>
#include <string>

namespace uampc::run_files {

class StreamedFile {
 public:
  // Creates (or empties) path; throws std::runtime_error naming path and the reason.
  explicit StreamedFile(const std::string& path);
  ~StreamedFile();  // closes without a word: close() is where a failure is reported
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;

  // Buffered: a failure shows at the write whose bytes overflowed the buffer, or at close().
  void write(const std::string& text);
  // Flushes and closes, checked; throws as write() does. A second call does nothing.
  void close();
  const std::string& path() const { return path_; }

 private:
  void fail(int error);

  std::string path_;
  std::FILE* file_ = nullptr;
  std::string failure_;  // the first failure; every later write repeats it
};

}  // namespace uampc::run_files
