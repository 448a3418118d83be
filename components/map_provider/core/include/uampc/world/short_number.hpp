// A number as people write it in a message ("0.4", "1e+06"): %g.
#pragma once

#include <cstdio>
#include <string>

namespace uampc::world {

inline std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace uampc::world
