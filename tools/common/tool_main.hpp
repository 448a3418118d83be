// What every development tool's command line needs: a main() that turns an exception into
// "NAME: message" and exit code 1 (bad command lines return 2 from run themselves), and a flag's
// number read strictly (a typo must not silently become 0, as atof makes it).
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

namespace uampc::tools {

// The whole of `text` as a finite number; throws std::invalid_argument naming the flag otherwise.
inline double number(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value)) {
    throw std::invalid_argument(flag + ": '" + text + "' is not a finite number");
  }
  return value;
}

// number(), and not negative: a duration, a noise, a standard deviation or a voxel size. A negative
// one would be taken silently (a std of -0.3 squares to the same information as 0.3).
inline double nonNegative(const std::string& flag, const std::string& text) {
  const double value = number(flag, text);
  if (value < 0.0) throw std::invalid_argument(flag + ": '" + text + "' must not be negative");
  return value;
}

// number(), and a whole number from 0 to INT_MAX: a count, a seed, a switch. A fraction or a value
// beyond int would otherwise be truncated or overflow the cast silently.
inline int count(const std::string& flag, const std::string& text) {
  const double value = nonNegative(flag, text);
  if (value != std::floor(value) || value > 2147483647.0) {
    throw std::invalid_argument(flag + ": '" + text + "' must be a whole number from 0 to 2147483647");
  }
  return static_cast<int>(value);
}

inline int runTool(const char* name, int (*run)(int, char**), int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace uampc::tools
