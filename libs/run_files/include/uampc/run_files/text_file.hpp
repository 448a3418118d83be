// Small text files read and written whole: markers, logs, report pages, security documents.
#pragma once

#include <string>

namespace uampc::run_files {

// The file's bytes; empty when it is missing or cannot be read (callers treat both as "nothing").
std::string readTextFile(const std::string& path);
// Replaces the file with `text`; throws std::runtime_error naming the file when that fails.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace uampc::run_files
