#include "uampc/runtime/yaml_printer.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

namespace uampc {
namespace {

// The shortest text that reads back as the same value, in the form PyYAML (and so `ros2 topic
// echo`) writes floats: Python's repr (positional for exponents -4 to 15, else scientific), always
// with a '.': "100.0", "1.0e-05", "1.0e+16".
template <typename Float>
std::string shortestFloat(Float value) {
  char text[64];
  const auto scientific = std::to_chars(text, text + sizeof text, value, std::chars_format::scientific);
  std::string result(text, scientific.ptr);
  const int exponent = std::stoi(result.substr(result.find('e') + 1));
  if (exponent >= -4 && exponent < 16) {
    const auto fixed = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed);
    result.assign(text, fixed.ptr);
  }
  if (result.find('.') == std::string::npos) {
    const auto e = result.find('e');
    result.insert(e == std::string::npos ? result.size() : e, ".0");
  }
  return result;
}

std::string shortestFloat(double value, bool single_precision) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return single_precision ? shortestFloat(static_cast<float>(value)) : shortestFloat(value);
}

bool isByteType(PrimitiveType type) {
  return type == PrimitiveType::kByte || type == PrimitiveType::kUInt8 || type == PrimitiveType::kChar;
}

// A plain scalar YAML would read as something else than this string (a number, a boolean, null), or
// that would not parse as one scalar (indicators, ": ", " #", flow punctuation).
bool needsQuotes(const std::string& text) {
  if (text.empty() || text.front() == ' ' || text.back() == ' ' || text.back() == ':') return true;
  if (std::string("-?:,[]{}#&*!|>'\"%@`").find(text.front()) != std::string::npos) return true;
  if (text.find(": ") != std::string::npos || text.find(" #") != std::string::npos) return true;
  if (text.find_first_of(",[]{}") != std::string::npos) return true;
  std::string lower;
  for (char c : text) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::set<std::string> special = {"true", "false", "yes", "no",   "on",   "off",  "y",
                                                "n",    "null",  "~",   ".nan", ".inf", "+.inf"};
  if (special.count(lower)) return true;
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return *end == '\0';  // reads as a number
}

bool hasControlCharacters(const std::string& text) {
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  }
  return false;
}

std::string doubleQuoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string singleQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

class YamlWriter {
 public:
  explicit YamlWriter(const YamlOptions& options) : options_(options) {}

  // The fields of a struct at `indent`; the first line starts with `first_prefix` instead (the
  // "- " of a sequence item) when it is given.
  void fields(const DecodedValue& s, std::size_t indent, const std::string& first_prefix = "") {
    bool first = true;
    for (const DecodedField& field : s.fields) {
      out_ += first && !first_prefix.empty() ? first_prefix : std::string(indent, ' ');
      out_ += field.name + ":";
      value(field.value, indent);
      first = false;
    }
  }

  std::string text() { return std::move(out_); }

 private:
  // A field's value, after "name:".
  void value(const DecodedValue& v, std::size_t indent) {
    switch (v.kind) {
      case DecodedValue::Kind::kScalar:
        out_ += " " + yamlScalar(v.scalar) + "\n";
        return;
      case DecodedValue::Kind::kString:
        out_ += " " + yamlString(v.text) + "\n";
        return;
      case DecodedValue::Kind::kStruct:
        out_ += "\n";
        fields(v, indent + 2);
        return;
      case DecodedValue::Kind::kScalars:
        out_ += " " + scalars(v) + "\n";
        return;
      case DecodedValue::Kind::kList:
        break;
    }
    if (v.elements.empty() || v.elements.front().kind == DecodedValue::Kind::kString) {
      out_ += " " + strings(v) + "\n";
      return;
    }
    out_ += "\n";
    for (const DecodedValue& element : v.elements) fields(element, indent + 2, std::string(indent, ' ') + "- ");
  }

  std::string scalars(const DecodedValue& v) const {
    if (!options_.full && isByteType(v.element_type) && v.scalars.size() > kLongestBytesShown) {
      return "<" + std::to_string(v.scalars.size()) + " bytes>";
    }
    std::string flow = "[";
    for (std::size_t i = 0; i < v.scalars.size(); ++i) flow += (i ? ", " : "") + yamlScalar(v.scalars[i]);
    return flow + "]";
  }

  static std::string strings(const DecodedValue& v) {
    std::string flow = "[";
    for (std::size_t i = 0; i < v.elements.size(); ++i) flow += (i ? ", " : "") + yamlString(v.elements[i].text);
    return flow + "]";
  }

  const YamlOptions& options_;
  std::string out_;
};

}  // namespace

std::string yamlScalar(const Scalar& value) {
  switch (value.type) {
    case PrimitiveType::kBool:
      return value.boolean ? "true" : "false";
    case PrimitiveType::kInt8:
    case PrimitiveType::kInt16:
    case PrimitiveType::kInt32:
    case PrimitiveType::kInt64:
      return std::to_string(value.signed_value);
    case PrimitiveType::kFloat32:
      return shortestFloat(value.real, true);
    case PrimitiveType::kFloat64:
      return shortestFloat(value.real, false);
    default:
      return std::to_string(value.unsigned_value);
  }
}

std::string yamlString(const std::string& text) {
  if (hasControlCharacters(text)) return doubleQuoted(text);
  return needsQuotes(text) ? singleQuoted(text) : text;
}

std::string toYaml(const DecodedValue& message, const YamlOptions& options) {
  YamlWriter writer(options);
  writer.fields(message, 0);
  return writer.text();
}

}  // namespace uampc
