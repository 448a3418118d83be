// CLI11 checks a number needs beyond CLI11's own, for `uampc` and the development tools: NaN and
// infinity pass CLI::NonNegativeNumber and CLI::Range (every comparison with NaN is false), so
// `uampc play --rate nan` played forever and `record --duration nan` never stopped; and counts
// whose message is readable.
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace uampc::command_line {

enum class Sign { kAny, kNonNegative, kPositive };

inline std::string finiteNumberProblem(const std::string& text, Sign sign) {
  double value = 0.0;
  if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value)) return "'" + text + "' is not a finite number";
  if (sign == Sign::kNonNegative && value < 0.0) return "'" + text + "' must not be negative";
  if (sign == Sign::kPositive && value <= 0.0) return "'" + text + "' must be more than 0";
  return {};
}

// A count: CLI::PositiveNumber's message names its bound, DBL_MAX, in 300 digits.
inline std::string positiveCountProblem(const std::string& text) {
  long long value = 0;
  if (!CLI::detail::lexical_cast(text, value) || value < 1) return "'" + text + "' is not a whole number of 1 or more";
  return {};
}

inline const CLI::Validator kFinite{[](std::string& text) { return finiteNumberProblem(text, Sign::kAny); },
                                    "NUMBER"};
inline const CLI::Validator kFiniteNonNegative{
    [](std::string& text) { return finiteNumberProblem(text, Sign::kNonNegative); }, "NUMBER >= 0"};
inline const CLI::Validator kFinitePositive{[](std::string& text) { return finiteNumberProblem(text, Sign::kPositive); },
                                            "NUMBER > 0"};
inline const CLI::Validator kPositiveCount{[](std::string& text) { return positiveCountProblem(text); }, "N >= 1"};

}  // namespace uampc::command_line
