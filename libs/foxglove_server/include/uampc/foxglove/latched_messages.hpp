// The latest messages of each latched channel (a transient-local topic), kept for subscriptions
// still to come. A DDS reader gets a latched topic's kept samples once, when it matches, and the
// viewer reads each channel with one reader for all its clients; so the server keeps them and
// starts each later subscription with them, as foxglove_bridge does
// (docs/decisions/viewer-latched-topics.md). Bounded per channel by the depth its owner gives:
// the reader's own history depth. Not thread-safe: the server guards it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>

#include "uampc/foxglove/protocol.hpp"
#include "uampc/foxglove/send_queues.hpp"

namespace uampc::foxglove {

struct KeptMessage {
  std::uint64_t time_ns = 0;
  Payload payload;
};

class LatchedMessages {
 public:
  // Keeps a message of a latched channel, dropping its oldest beyond `depth`.
  void keep(ChannelId channel, std::uint64_t time_ns, Payload payload, std::size_t depth);
  // What a new subscription to `channel` starts with, oldest first; empty for a channel not latched.
  const std::deque<KeptMessage>& of(ChannelId channel) const;
  void forget(ChannelId channel) { kept_.erase(channel); }
  std::size_t keptBytes() const;

 private:
  std::map<ChannelId, std::deque<KeptMessage>> kept_;
};

}  // namespace uampc::foxglove
