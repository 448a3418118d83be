// CLI11 checks the development tools' numbers need beyond CLI11's own: NaN and infinity pass
// CLI::NonNegativeNumber and CLI::Range (every comparison with NaN is false), so a typo such as
// `--duration nan` would run forever.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace uampc::tools {

inline std::string finiteNumberProblem(const std::string& text, bool non_negative) {
  double value = 0.0;
  if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return "'" + text + "' is not a finite number";
  if (non_negative && value < 0.0) return "'" + text + "' must not be negative";
  return {};
}

inline const CLI::Validator kFinite{[](std::string& text) { return finiteNumberProblem(text, false); }, "NUMBER"};
inline const CLI::Validator kFiniteNonNegative{[](std::string& text) { return finiteNumberProblem(text, true); },
                                               "NUMBER >= 0"};

}  // namespace uampc::tools
