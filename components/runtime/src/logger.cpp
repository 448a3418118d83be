#include "uampc/runtime/logger.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace uampc {

LogLevel logThreshold() {
  static const LogLevel threshold = [] {
    const char* env = std::getenv("UAMPC_LOG_LEVEL");
    if (!env) return LogLevel::kInfo;
    if (!std::strcmp(env, "debug")) return LogLevel::kDebug;
    if (!std::strcmp(env, "warn")) return LogLevel::kWarn;
    if (!std::strcmp(env, "error")) return LogLevel::kError;
    return LogLevel::kInfo;
  }();
  return threshold;
}

void Logger::write(LogLevel level, const std::string& text) const {
  if (level < logThreshold()) return;
  static const char* const kNames[] = {"DEBUG", "INFO ", "WARN ", "ERROR"};
  static std::mutex mutex;  // one line at a time, whichever thread logs
  const double t = clock_seconds_ ? clock_seconds_() : 0.0;
  std::lock_guard<std::mutex> lock(mutex);
  std::fprintf(stderr, "[%11.6f] [%s] %s %s\n", t, name_.c_str(), kNames[static_cast<int>(level)], text.c_str());
}

}  // namespace uampc
