// The main() of a development tool: run it, and turn an exception into "NAME: message" and exit
// code 1 (bad command lines return 2 from run themselves).
#pragma once

#include <cstdio>
#include <exception>

namespace uampc::tools {

inline int runTool(const char* name, int (*run)(int, char**), int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace uampc::tools
