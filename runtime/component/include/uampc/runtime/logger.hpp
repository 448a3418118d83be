// The one logger of uampc. Lines go to stderr as
//   [  12.345000] [motor] WARN  no command for 0.5 s; safe speed 0 rad/s
// with the component's clock time first, so a log reads in simulation time.
// A problem that repeats every scan or every step is said through a RateLimitedLog, below.
#pragma once

#include <functional>
#include <sstream>
#include <string>
#include <utility>

namespace uampc {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

// The level below which lines are dropped, from UAMPC_LOG_LEVEL (debug, info, warn, error).
LogLevel logThreshold();

// `text` with its control bytes (but newlines and tabs) written as \xNN: what a scene, a map
// header or a peer sent is quoted in messages, and a terminal must not act on it (an escape
// sequence that recolours or clears it). Every log line and scene error goes through it.
std::string printableText(const std::string& text);

class Logger {
 public:
  // clock_seconds gives the time printed in front of each line.
  Logger(std::string name, std::function<double()> clock_seconds)
      : name_(std::move(name)), clock_seconds_(std::move(clock_seconds)) {}

  template <typename... Parts>
  void debug(const Parts&... parts) const {
    write(LogLevel::kDebug, join(parts...));
  }
  template <typename... Parts>
  void info(const Parts&... parts) const {
    write(LogLevel::kInfo, join(parts...));
  }
  template <typename... Parts>
  void warn(const Parts&... parts) const {
    write(LogLevel::kWarn, join(parts...));
  }
  template <typename... Parts>
  void error(const Parts&... parts) const {
    write(LogLevel::kError, join(parts...));
  }

  void write(LogLevel level, const std::string& text) const;
  const std::string& name() const { return name_; }

  template <typename... Parts>
  static std::string join(const Parts&... parts) {
    std::ostringstream out;
    (out << ... << parts);
    return out.str();
  }

 private:
  std::string name_;
  std::function<double()> clock_seconds_;
};

// Says one kind of message only at some of its occurrences, so that a problem repeating every
// scan or every step does not drown the log. A component holds one per kind of message:
//   RateLimitedLog clamp_log_ = RateLimitedLog::once();
//   clamp_log_.warn(ctx_.log(), "command exceeds max_speed; clamping (said once)");
class RateLimitedLog {
 public:
  static RateLimitedLog once() { return RateLimitedLog(Schedule::kOnce, 0); }
  // The 1st, (n + 1)th, (2n + 1)th ... occurrence.
  static RateLimitedLog everyNth(long n);
  // The 1st, base-th, base^2-th ... occurrence (1st, 10th, 100th ... for base 10).
  static RateLimitedLog atPowersOf(long base);

  // Counts one occurrence; true if this one is to be said.
  bool due();
  // Occurrences counted since the start or the last reset().
  long occurrences() const { return occurrences_; }
  // Whether an occurrence was said since the start or the last reset().
  bool said() const { return occurrences_ > 0; }
  // The problem went away: its next occurrence is said again, counting from one.
  void reset() { occurrences_ = 0; }

  template <typename... Parts>
  void warn(const Logger& log, const Parts&... parts) {
    if (due()) log.warn(parts...);
  }
  template <typename... Parts>
  void error(const Logger& log, const Parts&... parts) {
    if (due()) log.error(parts...);
  }

 private:
  enum class Schedule { kOnce, kEveryNth, kPowers };
  RateLimitedLog(Schedule schedule, long step) : schedule_(schedule), step_(step) {}

  Schedule schedule_;
  long step_;  // n of everyNth, base of atPowersOf
  long occurrences_ = 0;
};

}  // namespace uampc
