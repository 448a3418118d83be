// Runs another program (openssl, sbatch, squeue, sacct) and waits for it: searched in PATH, stdin
// from /dev/null, stdout and stderr together into a scratch file that is read back and removed.
// A file, not a pipe: nothing to deadlock on, whatever the program prints.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace uampc::app {

struct ExternalCommandResult {
  bool started = false;  // false: not found or not executable (error says why)
  int exit_code = -1;    // -1 when it was killed by a signal
  std::string output;    // its stdout and stderr
  std::string error;     // why it did not start

  bool ok() const { return started && exit_code == 0; }
};

// argv[0] is the program. scratch_file: where its output goes while it runs (a directory of ours).
ExternalCommandResult runExternalCommand(const std::vector<std::string>& argv, const std::string& scratch_file);

// The command line as text, for messages.
std::string commandText(const std::vector<std::string>& argv);

}  // namespace uampc::app
