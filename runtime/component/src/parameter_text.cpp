#include "uampc/runtime/parameter_text.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

namespace uampc {
namespace {

ParameterValue asType(const ParameterSpec& spec, const YAML::Node& node) {
  switch (spec.type) {
    case ParameterType::kBool:
      return node.as<bool>();
    case ParameterType::kInt:
      return node.as<std::int64_t>();
    case ParameterType::kDouble:
      return node.as<double>();
    case ParameterType::kString:
    case ParameterType::kPath:
      return node.as<std::string>();
    case ParameterType::kDoubleList:
      return node.as<std::vector<double>>();
    case ParameterType::kStringList:
      return node.as<std::vector<std::string>>();
  }
  throw std::logic_error("unknown parameter type");
}

}  // namespace

ParameterValue parseParameterValue(const ParameterSpec& spec, const std::string& text) {
  auto fail = [&](const std::string& problem) { return std::invalid_argument("parameter '" + spec.name + "': " + problem); };
  ParameterValue value;
  try {
    value = asType(spec, YAML::Load(text));
  } catch (const YAML::Exception&) {
    throw fail("'" + text + "' is not of type " + toString(spec.type));
  }
  std::optional<double> number;
  if (const auto* i = std::get_if<std::int64_t>(&value)) number = static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&value)) number = *d;
  if (number && !std::isfinite(*number)) throw fail("must be a finite number, not " + text);
  if (number && !spec.withinBounds(*number)) throw fail(text + " is out of bounds " + spec.boundsText());
  if (const auto* s = std::get_if<std::string>(&value)) {
    if (!spec.choices.empty() && std::find(spec.choices.begin(), spec.choices.end(), *s) == spec.choices.end()) {
      std::string allowed;
      for (const auto& c : spec.choices) allowed += (allowed.empty() ? "" : ", ") + c;
      throw fail("'" + *s + "' is not one of " + allowed);
    }
    if (spec.type == ParameterType::kPath && !s->empty()) {
      const std::string path = std::filesystem::absolute(*s).lexically_normal().string();
      if (!std::filesystem::is_regular_file(path)) throw fail("no file " + path);
      value = path;
    }
  }
  return value;
}

}  // namespace uampc
