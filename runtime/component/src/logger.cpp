#include "uampc/runtime/logger.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>

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

std::string printableText(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n' && c != '\t') || byte == 0x7f) {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    } else {
      out += c;
    }
  }
  return out;
}

void Logger::write(LogLevel level, const std::string& text) const {
  if (level < logThreshold()) return;
  static const char* const kNames[] = {"DEBUG", "INFO ", "WARN ", "ERROR"};
  static std::mutex mutex;  // one line at a time, whichever thread logs
  const double t = clock_seconds_ ? clock_seconds_() : 0.0;
  std::lock_guard<std::mutex> lock(mutex);
  std::fprintf(stderr, "[%11.6f] [%s] %s %s\n", t, name_.c_str(), kNames[static_cast<int>(level)],
               printableText(text).c_str());
}

RateLimitedLog RateLimitedLog::everyNth(long n) {
  if (n < 1) throw std::invalid_argument("RateLimitedLog::everyNth needs n >= 1, got " + std::to_string(n));
  return RateLimitedLog(Schedule::kEveryNth, n);
}

RateLimitedLog RateLimitedLog::atPowersOf(long base) {
  if (base < 2) throw std::invalid_argument("RateLimitedLog::atPowersOf needs base >= 2, got " + std::to_string(base));
  return RateLimitedLog(Schedule::kPowers, base);
}

bool RateLimitedLog::due() {
  const long n = ++occurrences_;
  switch (schedule_) {
    case Schedule::kOnce:
      return n == 1;
    case Schedule::kEveryNth:
      return (n - 1) % step_ == 0;
    case Schedule::kPowers: {
      long power = 1;
      while (power < n) power *= step_;
      return power == n;
    }
  }
  return false;
}

}  // namespace uampc
