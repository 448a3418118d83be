#include "command_runner.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace uampc::test {

CommandResult runShell(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed for: " + command);
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  return result;
}

CommandResult runUampc(const std::string& args) {
  return runShell("UAMPC_COMPONENT_PATH=" + binaryPath("tests/components") + " " + binaryPath("bin/uampc") + " " +
                  args);
}

std::string sourcePath(const std::string& relative) { return std::string(UAMPC_SOURCE_DIR) + "/" + relative; }
std::string binaryPath(const std::string& relative) { return std::string(UAMPC_BINARY_DIR) + "/" + relative; }

std::string freshDirectory(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(UAMPC_BINARY_DIR) / "test_output" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string startWarnings(const std::string& output) {
  std::istringstream lines(output);
  std::string warnings;
  for (std::string line; std::getline(lines, line);) {
    const bool scene = line.find(": warning: ") != std::string::npos;
    const bool at_start = line.rfind("[   0.000000] [", 0) == 0 && line.find("] WARN ") != std::string::npos;
    if (scene || at_start) warnings += line + "\n";
  }
  return warnings;
}

}  // namespace uampc::test
