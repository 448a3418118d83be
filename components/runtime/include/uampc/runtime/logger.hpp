// The one logger of uampc. Lines go to stderr as
//   [  12.345000] [motor] WARN  no command for 0.5 s; safe speed 0 rad/s
// with the component's clock time first, so a log reads in simulation time.
#pragma once

#include <functional>
#include <sstream>
#include <string>
#include <utility>

namespace uampc {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

// The level below which lines are dropped, from UAMPC_LOG_LEVEL (debug, info, warn, error).
LogLevel logThreshold();

class Logger {
 public:
  // clock_seconds gives the time printed in front of each line.
  Logger(std::string name, std::function<double()> clock_seconds)
      : name_(std::move(name)), clock_seconds_(std::move(clock_seconds)) {}

  template <typename... Parts>
  void debug(const Parts&... parts) const { write(LogLevel::kDebug, join(parts...)); }
  template <typename... Parts>
  void info(const Parts&... parts) const { write(LogLevel::kInfo, join(parts...)); }
  template <typename... Parts>
  void warn(const Parts&... parts) const { write(LogLevel::kWarn, join(parts...)); }
  template <typename... Parts>
  void error(const Parts&... parts) const { write(LogLevel::kError, join(parts...)); }

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

}  // namespace uampc
