// Runs the real uampc command from tests, as a user would, and captures what it prints.
#pragma once

#include <string>

namespace uampc::test {

struct CommandResult {
  int exit_code = -1;  // -1: did not exit normally
  std::string output;  // stdout and stderr together
};

// Runs `uampc ARGS` with the test components on UAMPC_COMPONENT_PATH.
CommandResult runUampc(const std::string& args);
// Runs any shell command line.
CommandResult runShell(const std::string& command);

std::string sourcePath(const std::string& relative);  // inside the source tree
std::string binaryPath(const std::string& relative);  // inside the build tree
// A fresh empty directory under the build tree's test output folder.
std::string freshDirectory(const std::string& name);
std::string readFile(const std::string& path);
// The warnings a run printed as it started, one per line: the scene's ("file:line:column: warning:")
// and its components' while sim time was 0 (constructing, the first step).
std::string startWarnings(const std::string& output);

}  // namespace uampc::test
