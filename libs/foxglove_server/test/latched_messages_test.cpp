#include "uampc/foxglove/latched_messages.hpp"

#include <gtest/gtest.h>

namespace uampc::foxglove {
namespace {

Payload keptPayload(std::uint8_t tag) { return std::make_shared<const std::vector<std::uint8_t>>(10, tag); }

TEST(LatchedMessages, KeepsTheLatestUpToTheDepthPerChannel) {
  LatchedMessages latched;
  for (std::uint8_t i = 0; i < 5; ++i) latched.keep(1, i, keptPayload(i), 3);
  latched.keep(2, 9, keptPayload(9), 3);
  ASSERT_EQ(latched.of(1).size(), 3u);
  EXPECT_EQ(latched.of(1).front().time_ns, 2u);  // 0 and 1 gave way
  EXPECT_EQ(latched.of(1).back().time_ns, 4u);
  EXPECT_EQ(latched.of(2).size(), 1u);
  EXPECT_TRUE(latched.of(3).empty());
  EXPECT_EQ(latched.keptBytes(), 40u);
  latched.forget(1);
  EXPECT_TRUE(latched.of(1).empty());
  EXPECT_EQ(latched.keptBytes(), 10u);
}

}  // namespace
}  // namespace uampc::foxglove
