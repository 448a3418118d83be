// What one client has yet to be sent: a bounded queue per subscription, within a bound on the
// client's bytes. A client that reads slower than the run writes loses its oldest messages,
// counted per subscription, and never holds up the run or the other clients. The queues hold
// shared payloads: a message waiting for 500 subscriptions and 16 clients is in memory once
// (docs/decisions/live-viewer.md, docs/decisions/viewer-memory-bounds.md). Not thread-safe: the
// server guards it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "uampc/foxglove/protocol.hpp"

namespace uampc::foxglove {

// A message's bytes as they arrived (a sample's CDR), immutable and shared by every subscription
// and client it goes to.
using Payload = std::shared_ptr<const std::vector<std::uint8_t>>;

// One message for one subscription; its frame's header is made when it is sent.
struct QueuedMessage {
  SubscriptionId subscription = 0;
  std::uint64_t time_ns = 0;
  Payload payload;
  // What it takes in the client's socket once sent, the bytes it is counted at while it waits.
  std::size_t frameBytes() const { return kMessageDataHeaderBytes + payload->size(); }
};

class SendQueues {
 public:
  // max_bytes: what the client's messages in waiting, and its socket's bytes not yet written, may
  // come to together (each message counted in full, shared or not).
  SendQueues(std::size_t depth_per_subscription, std::size_t max_bytes)
      : depth_(depth_per_subscription), max_bytes_(max_bytes) {}

  // depth: this subscription's own, for one that starts with more kept messages than the usual
  // depth (a latched topic's); 0: the usual.
  void add(SubscriptionId id, std::size_t depth = 0);
  void remove(SubscriptionId id);
  bool has(SubscriptionId id) const { return queues_.count(id) > 0; }
  std::size_t subscriptions() const { return queues_.size(); }

  // Queues a message for its subscription, sharing its payload. When that subscription's queue is
  // full, its oldest message is dropped; then, while the client's bytes (queued here, and
  // `socket_bytes` its socket holds) exceed max_bytes, its oldest messages of any subscription
  // are, but never this one: a message larger than the bound still goes, alone. Drops are counted.
  // Returns false when there is no such subscription.
  bool push(QueuedMessage message, std::size_t socket_bytes = 0);

  // The next message to send, taking the subscriptions in turn so that one busy topic does not
  // starve the others; nullopt when everything is sent. `fits` says whether the socket takes a
  // frame of that many bytes now; when it does not, the message stays first in its queue.
  template <typename Fits>
  std::optional<QueuedMessage> pop(Fits&& fits);
  std::optional<QueuedMessage> pop() {
    return pop([](std::size_t) { return true; });
  }

  // Messages dropped since the last call, by subscription (only those that dropped any).
  std::map<SubscriptionId, std::uint64_t> takeNewDrops();
  std::uint64_t totalDrops() const { return total_drops_; }
  std::size_t queuedFrames() const;
  std::size_t queuedBytes() const { return queued_bytes_; }  // frameBytes() of every message waiting

 private:
  struct Waiting {
    QueuedMessage message;
    std::uint64_t order;  // when it was queued, for dropping the client's oldest first
  };
  struct Queue {
    std::deque<Waiting> messages;
    std::size_t depth = 0;
    std::uint64_t new_drops = 0;
  };
  void dropFront(Queue& queue);
  // The queue whose first message is the client's oldest but `keep`; nullptr if there is none.
  Queue* oldestExcept(std::uint64_t keep);
  std::optional<QueuedMessage> takeFront(std::map<SubscriptionId, Queue>::iterator queue);

  std::size_t depth_;
  std::size_t max_bytes_;
  std::map<SubscriptionId, Queue> queues_;
  SubscriptionId next_turn_ = 0;  // pop starts at the first subscription id >= this
  std::uint64_t next_order_ = 0;
  std::size_t queued_bytes_ = 0;
  std::uint64_t total_drops_ = 0;
};

template <typename Fits>
std::optional<QueuedMessage> SendQueues::pop(Fits&& fits) {
  if (queues_.empty()) return std::nullopt;
  // Round robin: from the subscription whose turn it is, wrapping around once.
  auto start = queues_.lower_bound(next_turn_);
  if (start == queues_.end()) start = queues_.begin();
  auto it = start;
  do {
    if (!it->second.messages.empty()) {
      // The turn stays here when the socket is full: this message is the next to go.
      if (!fits(it->second.messages.front().message.frameBytes())) return std::nullopt;
      return takeFront(it);
    }
    if (++it == queues_.end()) it = queues_.begin();
  } while (it != start);
  return std::nullopt;
}

}  // namespace uampc::foxglove
