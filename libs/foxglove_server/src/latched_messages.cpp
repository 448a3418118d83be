#include "uampc/foxglove/latched_messages.hpp"

namespace uampc::foxglove {

void LatchedMessages::keep(ChannelId channel, std::uint64_t time_ns, Payload payload, std::size_t depth) {
  auto& kept = kept_[channel];
  kept.push_back({time_ns, std::move(payload)});
  while (kept.size() > depth) kept.pop_front();
}

const std::deque<KeptMessage>& LatchedMessages::of(ChannelId channel) const {
  static const std::deque<KeptMessage> kNone;
  const auto kept = kept_.find(channel);
  return kept == kept_.end() ? kNone : kept->second;
}

std::size_t LatchedMessages::keptBytes() const {
  std::size_t bytes = 0;
  for (const auto& [channel, kept] : kept_) {
    for (const KeptMessage& m : kept) bytes += m.payload->size();
  }
  return bytes;
}

}  // namespace uampc::foxglove
