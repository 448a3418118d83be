// Small text files read and written whole: markers, logs, report pages, security documents, and
// every run file that is written in one go (metrics.json, run_info.json, trajectories, snapshots).
#pragma once

#include <string>

namespace uampc::run_files {

// The file's bytes; empty when it is missing or cannot be read (callers treat both as "nothing").
std::string readTextFile(const std::string& path);

// Replaces the file with `text` (any bytes), whole or not at all: the bytes go to
// path + ".partial", which is renamed to path once every byte was written and the file closed
// without error. On failure (a full disk, a read-only directory, a name too long) the partial file
// is removed, path is left as it was, and std::runtime_error says "cannot write PATH: REASON"
// (docs/decisions/run-files-whole-or-absent.md).
void writeTextFile(const std::string& path, const std::string& text);

// Appends `text` to the file (made if missing), whole or not at all: every byte is written and the
// file closed without error, or the file is cut back to the size it had and std::runtime_error says
// "cannot write PATH: REASON". For append-only logs read back line by line (the Slurm backend's
// job ids), where a line cut short would read as another line.
void appendToTextFile(const std::string& path, const std::string& text);

// "cannot write PATH: REASON", REASON being strerror(error): the one wording of a failed write.
std::string cannotWrite(const std::string& path, int error);

}  // namespace uampc::run_files
