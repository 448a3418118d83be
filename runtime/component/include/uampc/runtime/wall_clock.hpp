// The wall clock (system_clock, Unix epoch): the scene's time in real-time mode, for the runtime and
// the tools beside a running system. Components never read it; they ask Context::now().
#pragma once

#include <chrono>

#include "uampc/runtime/time.hpp"

namespace uampc {

inline Time wallNow() {
  return Time{std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
                  .count()};
}

}  // namespace uampc
