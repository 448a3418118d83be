#include <gtest/gtest.h>

#include <vector>

#include "uampc/runtime/logger.hpp"

namespace uampc {
namespace {

// The occurrences (1-based) among the first `count` that the log says.
std::vector<long> saidOccurrences(RateLimitedLog log, long count) {
  std::vector<long> said;
  for (long i = 1; i <= count; ++i) {
    if (log.due()) said.push_back(i);
  }
  return said;
}

TEST(RateLimitedLog, OnceSaysTheFirstOccurrenceOnly) {
  EXPECT_EQ(saidOccurrences(RateLimitedLog::once(), 50), (std::vector<long>{1}));
}

TEST(RateLimitedLog, EveryNthSaysTheFirstAndThenEveryNth) {
  EXPECT_EQ(saidOccurrences(RateLimitedLog::everyNth(4), 13), (std::vector<long>{1, 5, 9, 13}));
  EXPECT_EQ(saidOccurrences(RateLimitedLog::everyNth(1), 3), (std::vector<long>{1, 2, 3}));
}

TEST(RateLimitedLog, PowersSayTheFirstThenEachPower) {
  EXPECT_EQ(saidOccurrences(RateLimitedLog::atPowersOf(10), 1000), (std::vector<long>{1, 10, 100, 1000}));
  EXPECT_EQ(saidOccurrences(RateLimitedLog::atPowersOf(2), 9), (std::vector<long>{1, 2, 4, 8}));
}

TEST(RateLimitedLog, ResetSaysTheNextOccurrenceAgain) {
  RateLimitedLog log = RateLimitedLog::once();
  EXPECT_FALSE(log.said());
  EXPECT_TRUE(log.due());
  EXPECT_FALSE(log.due());
  EXPECT_TRUE(log.said());
  EXPECT_EQ(log.occurrences(), 2);
  log.reset();
  EXPECT_FALSE(log.said());
  EXPECT_TRUE(log.due());
}

TEST(RateLimitedLog, RejectsScheduleThatNeverRepeats) {
  EXPECT_THROW(RateLimitedLog::everyNth(0), std::invalid_argument);
  EXPECT_THROW(RateLimitedLog::atPowersOf(1), std::invalid_argument);
}

TEST(RateLimitedLog, WarnWritesOnlyWhenDue) {
  if (logThreshold() > LogLevel::kWarn) GTEST_SKIP() << "UAMPC_LOG_LEVEL hides warnings";
  const Logger logger("motor", [] { return 1.5; });
  RateLimitedLog log = RateLimitedLog::everyNth(2);
  testing::internal::CaptureStderr();
  for (int i = 1; i <= 4; ++i) log.warn(logger, "occurrence ", i);
  const std::string text = testing::internal::GetCapturedStderr();
  EXPECT_NE(text.find("[motor] WARN  occurrence 1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("[motor] WARN  occurrence 3\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("occurrence 2"), std::string::npos) << text;
  EXPECT_EQ(text.find("occurrence 4"), std::string::npos) << text;
}

}  // namespace
}  // namespace uampc
