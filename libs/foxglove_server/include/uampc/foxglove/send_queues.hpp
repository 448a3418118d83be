// What one client has yet to be sent: a bounded queue per subscription. A client that reads slower
// than the run writes loses its oldest messages, counted per subscription, and never holds up the
// run or the other clients (docs/decisions/live-viewer.md). Not thread-safe: the server guards it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "uampc/foxglove/protocol.hpp"

namespace uampc::foxglove {

using Frame = std::shared_ptr<const std::vector<std::uint8_t>>;

class SendQueues {
 public:
  explicit SendQueues(std::size_t depth_per_subscription) : depth_(depth_per_subscription) {}

  void add(SubscriptionId id) { queues_.try_emplace(id); }
  void remove(SubscriptionId id) { queues_.erase(id); }
  bool has(SubscriptionId id) const { return queues_.count(id) > 0; }
  std::size_t subscriptions() const { return queues_.size(); }

  // Queues a frame for a subscription; when its queue is full, the oldest frame is dropped and
  // counted. Returns false when there is no such subscription.
  bool push(SubscriptionId id, Frame frame);

  // The next frame to send, taking the subscriptions in turn so that one busy topic does not
  // starve the others; nullptr when everything is sent.
  Frame pop();

  // Frames dropped since the last call, by subscription (only those that dropped any).
  std::map<SubscriptionId, std::uint64_t> takeNewDrops();
  std::uint64_t totalDrops() const { return total_drops_; }
  std::size_t queuedFrames() const;

 private:
  struct Queue {
    std::deque<Frame> frames;
    std::uint64_t new_drops = 0;
  };
  std::size_t depth_;
  std::map<SubscriptionId, Queue> queues_;
  SubscriptionId next_turn_ = 0;  // pop starts at the first subscription id >= this
  std::uint64_t total_drops_ = 0;
};

}  // namespace uampc::foxglove
