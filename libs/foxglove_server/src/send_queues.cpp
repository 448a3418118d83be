#include "uampc/foxglove/send_queues.hpp"

namespace uampc::foxglove {

bool SendQueues::push(SubscriptionId id, Frame frame) {
  const auto queue = queues_.find(id);
  if (queue == queues_.end()) return false;
  auto& frames = queue->second.frames;
  frames.push_back(std::move(frame));
  while (frames.size() > depth_) {
    frames.pop_front();
    ++queue->second.new_drops;
    ++total_drops_;
  }
  return true;
}

Frame SendQueues::pop() {
  if (queues_.empty()) return nullptr;
  // Round robin: from the subscription whose turn it is, wrapping around once.
  auto start = queues_.lower_bound(next_turn_);
  if (start == queues_.end()) start = queues_.begin();
  auto it = start;
  do {
    if (!it->second.frames.empty()) {
      Frame frame = std::move(it->second.frames.front());
      it->second.frames.pop_front();
      next_turn_ = it->first + 1;  // wraps to 0 past the largest id, which lower_bound handles
      return frame;
    }
    if (++it == queues_.end()) it = queues_.begin();
  } while (it != start);
  return nullptr;
}

std::map<SubscriptionId, std::uint64_t> SendQueues::takeNewDrops() {
  std::map<SubscriptionId, std::uint64_t> drops;
  for (auto& [id, queue] : queues_) {
    if (queue.new_drops == 0) continue;
    drops[id] = queue.new_drops;
    queue.new_drops = 0;
  }
  return drops;
}

std::size_t SendQueues::queuedFrames() const {
  std::size_t n = 0;
  for (const auto& [id, queue] : queues_) n += queue.frames.size();
  return n;
}

}  // namespace uampc::foxglove
