// Time in uampc: integer nanoseconds, so that lockstep steps add up exactly and runs are
// deterministic. Components never read the wall clock; they ask Context::now().
#pragma once

#include <cstdint>

#include "builtin_interfaces/msg/Time.h"

namespace uampc {

struct Time {
  std::int64_t ns = 0;

  static Time fromSeconds(double s) { return Time{static_cast<std::int64_t>(s * 1e9 + (s >= 0 ? 0.5 : -0.5))}; }
  double seconds() const { return static_cast<double>(ns) * 1e-9; }

  friend bool operator<(Time a, Time b) { return a.ns < b.ns; }
  friend bool operator<=(Time a, Time b) { return a.ns <= b.ns; }
  friend bool operator>(Time a, Time b) { return a.ns > b.ns; }
  friend bool operator>=(Time a, Time b) { return a.ns >= b.ns; }
  friend bool operator==(Time a, Time b) { return a.ns == b.ns; }
  friend bool operator!=(Time a, Time b) { return a.ns != b.ns; }
  friend Time operator+(Time a, Time b) { return Time{a.ns + b.ns}; }
  friend Time operator-(Time a, Time b) { return Time{a.ns - b.ns}; }
};

// builtin_interfaces/Time counts seconds and nanoseconds, as ROS 2 does.
inline builtin_interfaces::msg::Time toMsg(Time t) {
  builtin_interfaces::msg::Time m;
  std::int64_t sec = t.ns / 1000000000;
  std::int64_t nsec = t.ns % 1000000000;
  if (nsec < 0) {
    nsec += 1000000000;
    sec -= 1;
  }
  m.sec(static_cast<std::int32_t>(sec));
  m.nanosec(static_cast<std::uint32_t>(nsec));
  return m;
}

inline Time fromMsg(const builtin_interfaces::msg::Time& m) {
  return Time{static_cast<std::int64_t>(m.sec()) * 1000000000 + m.nanosec()};
}

}  // namespace uampc
