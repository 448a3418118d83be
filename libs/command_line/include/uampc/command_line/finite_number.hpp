// CLI11 checks a number needs beyond CLI11's own, for `uampc` and the development tools: NaN and
// infinity pass CLI::NonNegativeNumber and CLI::Range (every comparison with NaN is false), so
// `uampc play --rate nan` played forever and `record --duration nan` never stopped.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace uampc::command_line {

inline std::string finiteNumberProblem(const std::string& text, bool non_negative) {
  double value = 0.0;
  if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return "'" + text + "' is not a finite number";
  if (non_negative && value < 0.0) return "'" + text + "' must not be negative";
  return {};
}

inline const CLI::Validator kFinite{[](std::string& text) { return finiteNumberProblem(text, false); }, "NUMBER"};
inline const CLI::Validator kFiniteNonNegative{[](std::string& text) { return finiteNumberProblem(text, true); },
                                               "NUMBER >= 0"};

}  // namespace uampc::command_line
