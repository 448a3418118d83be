#include "uampc/runtime/parameter.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "uampc/runtime/qos.hpp"

namespace uampc {

const char* toString(ParameterType type) {
  switch (type) {
    case ParameterType::kBool: return "bool";
    case ParameterType::kInt: return "int";
    case ParameterType::kDouble: return "double";
    case ParameterType::kString: return "string";
    case ParameterType::kPath: return "path";
    case ParameterType::kDoubleList: return "double list";
    case ParameterType::kStringList: return "string list";
  }
  return "?";
}

std::string formatNumber(double value) {
  char text[32];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(text, sizeof text, "%.*g", precision, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

std::string toString(const ParameterValue& value) {
  std::ostringstream out;
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) out << (v ? "true" : "false");
        else if constexpr (std::is_same_v<T, std::string>) out << '"' << v << '"';
        else if constexpr (std::is_same_v<T, std::vector<double>>) {
          out << '[';
          for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << formatNumber(v[i]);
          out << ']';
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          out << '[';
          for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << '"' << v[i] << '"';
          out << ']';
        } else if constexpr (std::is_same_v<T, double>) out << formatNumber(v);
        else out << v;
      },
      value);
  return out.str();
}

const char* toString(QosPreset preset) {
  switch (preset) {
    case QosPreset::kSensor: return "sensor";
    case QosPreset::kControl: return "control";
    case QosPreset::kLatched: return "latched";
  }
  return "?";
}

bool ParameterSpec::withinBounds(double v) const {
  if (zero_is_off && v == 0.0) return true;
  return !((min && v < *min) || (max && v > *max));
}

std::string ParameterSpec::boundsText() const {
  if (!min && !max) return {};
  return "[" + (min ? formatNumber(*min) : std::string("-inf")) + ", " + (max ? formatNumber(*max) : std::string("inf")) +
         "]" + (zero_is_off ? " or 0 (off)" : "");
}

}  // namespace uampc
