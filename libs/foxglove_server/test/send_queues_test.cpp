#include "uampc/foxglove/send_queues.hpp"

#include <gtest/gtest.h>

namespace uampc::foxglove {
namespace {

Frame frame(std::uint8_t tag) { return std::make_shared<const std::vector<std::uint8_t>>(1, tag); }

TEST(SendQueues, AFullQueueDropsItsOldestAndCountsThem) {
  SendQueues q(3);
  q.add(1);
  for (std::uint8_t i = 0; i < 5; ++i) EXPECT_TRUE(q.push(1, frame(i)));
  EXPECT_EQ(q.totalDrops(), 2u);
  EXPECT_EQ(q.takeNewDrops(), (std::map<SubscriptionId, std::uint64_t>{{1, 2}}));
  EXPECT_TRUE(q.takeNewDrops().empty());  // said once
  EXPECT_EQ((*q.pop())[0], 2);            // 0 and 1 were dropped
  EXPECT_EQ((*q.pop())[0], 3);
  EXPECT_EQ((*q.pop())[0], 4);
  EXPECT_EQ(q.pop(), nullptr);
}

TEST(SendQueues, SubscriptionsTakeTurns) {
  SendQueues q(10);
  q.add(1);
  q.add(2);
  for (std::uint8_t i = 0; i < 3; ++i) q.push(1, frame(10 + i));
  q.push(2, frame(20));
  std::vector<int> order;
  while (Frame f = q.pop()) order.push_back((*f)[0]);
  EXPECT_EQ(order, (std::vector<int>{10, 20, 11, 12}));
}

TEST(SendQueues, UnknownAndRemovedSubscriptionsTakeNothing) {
  SendQueues q(2);
  EXPECT_FALSE(q.push(9, frame(1)));
  q.add(9);
  q.push(9, frame(1));
  q.remove(9);
  EXPECT_EQ(q.pop(), nullptr);
  EXPECT_EQ(q.queuedFrames(), 0u);
}

}  // namespace
}  // namespace uampc::foxglove
