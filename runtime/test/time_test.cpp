#include <gtest/gtest.h>

#include "uampc/runtime/time.hpp"

namespace uampc {
namespace {

TEST(Time, RoundTripsThroughBuiltinInterfacesTime) {
  for (std::int64_t ns : {0LL, 1LL, 999999999LL, 1000000000LL, 1644823132492110014LL, -1LL, -1500000000LL}) {
    const auto msg = toMsg(Time{ns});
    EXPECT_LT(msg.nanosec(), 1000000000u);
    EXPECT_EQ(fromMsg(msg).ns, ns);
  }
}

TEST(Time, SecondsConversionRoundsToNearestNanosecond) {
  EXPECT_EQ(Time::fromSeconds(0.005).ns, 5000000);
  EXPECT_EQ(Time::fromSeconds(-0.005).ns, -5000000);
  EXPECT_DOUBLE_EQ(Time{2500000000}.seconds(), 2.5);
}

}  // namespace
}  // namespace uampc
