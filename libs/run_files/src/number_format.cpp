#include "uampc/run_files/number_format.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace uampc::run_files {

std::string formatDouble(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (error != std::errc()) throw std::runtime_error("formatDouble: cannot format a double");
  return std::string(buffer, end);
}

}  // namespace uampc::run_files
