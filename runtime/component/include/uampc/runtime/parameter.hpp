// Parameters a component declares, and the values a scene gives them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace uampc {

enum class ParameterType {
  kBool,
  kInt,
  kDouble,
  kString,
  kPath,        // a string naming a file that must exist; relative paths are from the scene file
  kDoubleList,
  kStringList,  // e.g. topics: [/lidar/points, /motor/state]
};

const char* toString(ParameterType type);

using ParameterValue =
    std::variant<bool, std::int64_t, double, std::string, std::vector<double>, std::vector<std::string>>;

// Human-readable value, as it would be written in YAML (and valid JSON for numbers and lists).
std::string toString(const ParameterValue& value);
// The shortest decimal text that reads back as the same double: 3.6, not 3.6000000000000001.
std::string formatNumber(double value);

struct ParameterSpec {
  std::string name;
  ParameterType type = ParameterType::kDouble;
  std::optional<ParameterValue> default_value;  // none: the parameter is required
  std::string doc;
  std::optional<double> min;                    // numeric bounds, inclusive
  std::optional<double> max;
  bool zero_is_off = false;                     // 0 is allowed besides [min, max]: it switches off
  std::vector<std::string> choices;             // allowed strings; empty: any
  std::size_t list_length = 0;                  // a list of numbers of exactly this many; 0: any
                                                // (or none, when the default is the empty list)
  // Part of the rig (the LiDAR, its model and its mounting on the motor): set once in the scene's
  // rig: block and given to every component that declares it, never in one component's params.
  bool rig = false;
  // A rig parameter this one may not be given beside in a rig: block: two ways to say one fact
  // (lidar_rotation_rpy_deg and tilt_deg). Empty: none.
  std::string not_with;

  bool required() const { return !default_value.has_value(); }
  // Whether a number lies within [min, max], or is 0 where 0 switches off: the one bounds rule of
  // scenes, --set, tools and tests.
  bool withinBounds(double v) const;
  // The bounds as messages and listings write them: "[0.05, 10] or 0 (off)"; empty without bounds.
  std::string boundsText() const;

  // Fluent setters used in Component::describe().
  ParameterSpec& atLeast(double v) { min = v; return *this; }
  ParameterSpec& atMost(double v) { max = v; return *this; }
  ParameterSpec& between(double lo, double hi) { min = lo; max = hi; return *this; }
  ParameterSpec& orOff() { zero_is_off = true; return *this; }
  ParameterSpec& oneOf(std::vector<std::string> allowed) { choices = std::move(allowed); return *this; }
  ParameterSpec& ofLength(std::size_t n) { list_length = n; return *this; }
  ParameterSpec& partOfRig() { rig = true; return *this; }
  ParameterSpec& notWith(std::string other) { not_with = std::move(other); return *this; }
};

}  // namespace uampc
