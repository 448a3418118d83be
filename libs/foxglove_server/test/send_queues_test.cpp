#include "uampc/foxglove/send_queues.hpp"

#include <gtest/gtest.h>

#include <set>

namespace uampc::foxglove {
namespace {

constexpr std::size_t kNoByteBound = std::size_t(1) << 40;

Payload payload(std::uint8_t tag, std::size_t size = 1) {
  return std::make_shared<const std::vector<std::uint8_t>>(size, tag);
}
QueuedMessage message(SubscriptionId id, std::uint8_t tag, std::size_t size = 1) {
  return {id, tag, payload(tag, size)};
}
int tagOf(const std::optional<QueuedMessage>& m) { return m ? (*m->payload)[0] : -1; }

TEST(SendQueues, AFullQueueDropsItsOldestAndCountsThem) {
  SendQueues q(3, kNoByteBound);
  q.add(1);
  for (std::uint8_t i = 0; i < 5; ++i) EXPECT_TRUE(q.push(message(1, i)));
  EXPECT_EQ(q.totalDrops(), 2u);
  EXPECT_EQ(q.takeNewDrops(), (std::map<SubscriptionId, std::uint64_t>{{1, 2}}));
  EXPECT_TRUE(q.takeNewDrops().empty());  // said once
  EXPECT_EQ(tagOf(q.pop()), 2);           // 0 and 1 were dropped
  EXPECT_EQ(tagOf(q.pop()), 3);
  EXPECT_EQ(tagOf(q.pop()), 4);
  EXPECT_FALSE(q.pop());
}

TEST(SendQueues, SubscriptionsTakeTurns) {
  SendQueues q(10, kNoByteBound);
  q.add(1);
  q.add(2);
  for (std::uint8_t i = 0; i < 3; ++i) q.push(message(1, 10 + i));
  q.push(message(2, 20));
  std::vector<int> order;
  while (auto m = q.pop()) order.push_back(tagOf(m));
  EXPECT_EQ(order, (std::vector<int>{10, 20, 11, 12}));
}

TEST(SendQueues, UnknownAndRemovedSubscriptionsTakeNothing) {
  SendQueues q(2, kNoByteBound);
  EXPECT_FALSE(q.push(message(9, 1)));
  q.add(9);
  q.push(message(9, 1));
  q.remove(9);
  EXPECT_FALSE(q.pop());
  EXPECT_EQ(q.queuedFrames(), 0u);
  EXPECT_EQ(q.queuedBytes(), 0u);
}

// The viewer's memory went with subscriptions times clients because each queue held a copy of
// every frame (docs/decisions/viewer-memory-bounds.md): a payload is now held, not copied.
TEST(SendQueues, OnePayloadServesEverySubscriptionWithoutACopy) {
  SendQueues q(10, kNoByteBound);
  const Payload scan = payload(7, 100000);
  for (SubscriptionId id = 0; id < 500; ++id) {
    q.add(id);
    q.push({id, 5, scan});
  }
  EXPECT_EQ(scan.use_count(), 501);  // this test's and the 500 queues': one payload in memory
  // Counted at what each costs once sent (the socket's copy), header included.
  EXPECT_EQ(q.queuedBytes(), 500 * (kMessageDataHeaderBytes + 100000));
  std::set<SubscriptionId> served;
  while (auto m = q.pop()) {
    EXPECT_EQ(m->payload.get(), scan.get());
    served.insert(m->subscription);
  }
  EXPECT_EQ(served.size(), 500u);
  EXPECT_EQ(scan.use_count(), 1);
  EXPECT_EQ(q.queuedBytes(), 0u);
}

TEST(SendQueues, TheByteBoundDropsTheClientsOldestFirst) {
  const std::size_t frame = kMessageDataHeaderBytes + 100;
  SendQueues q(10, 5 * frame);
  q.add(1);
  q.add(2);
  for (std::uint8_t i = 0; i < 8; ++i) q.push(message(1 + i % 2, i, 100));
  EXPECT_EQ(q.queuedBytes(), 5 * frame);
  EXPECT_EQ(q.totalDrops(), 3u);
  EXPECT_EQ(q.takeNewDrops(), (std::map<SubscriptionId, std::uint64_t>{{1, 2}, {2, 1}}));  // 0, 2 and 1
  std::multiset<int> left;
  while (auto m = q.pop()) left.insert(tagOf(m));
  EXPECT_EQ(left, (std::multiset<int>{3, 4, 5, 6, 7}));
}

TEST(SendQueues, TheSocketsBytesCountTowardsTheBound) {
  const std::size_t frame = kMessageDataHeaderBytes + 100;
  SendQueues q(10, 5 * frame);
  q.add(1);
  for (std::uint8_t i = 0; i < 4; ++i) q.push(message(1, i, 100));
  q.push(message(1, 4, 100), 3 * frame);  // three frames' worth still in the socket
  EXPECT_EQ(q.queuedBytes(), 2 * frame);
  EXPECT_EQ(tagOf(q.pop()), 3);
}

// A latched map larger than the bound must still reach the client: alone, after what was older.
TEST(SendQueues, AMessageLargerThanTheBoundGoesAlone) {
  SendQueues q(10, 1000);
  q.add(1);
  q.add(2);
  q.push(message(1, 1, 100));
  q.push(message(2, 2, 5000), 400);
  EXPECT_EQ(q.queuedFrames(), 1u);
  EXPECT_EQ(tagOf(q.pop()), 2);
  EXPECT_EQ(q.totalDrops(), 1u);
}

TEST(SendQueues, ASubscriptionMayKeepMoreThanTheUsualDepth) {
  SendQueues q(2, kNoByteBound);
  q.add(1, 5);  // a latched topic's kept samples, all of them
  for (std::uint8_t i = 0; i < 5; ++i) q.push(message(1, i));
  EXPECT_EQ(q.queuedFrames(), 5u);
  EXPECT_EQ(q.totalDrops(), 0u);
}

TEST(SendQueues, AMessageTheSocketCannotTakeWaitsFirstInLine) {
  SendQueues q(10, kNoByteBound);
  q.add(1);
  q.push(message(1, 1, 50));
  q.push(message(1, 2, 50));
  EXPECT_FALSE(q.pop([](std::size_t) { return false; }));
  EXPECT_EQ(tagOf(q.pop()), 1);
}

}  // namespace
}  // namespace uampc::foxglove
