#include "uampc/foxglove/send_queues.hpp"

namespace uampc::foxglove {

void SendQueues::add(SubscriptionId id, std::size_t depth) {
  Queue& queue = queues_[id];
  queue.depth = depth > depth_ ? depth : depth_;
}

void SendQueues::remove(SubscriptionId id) {
  const auto queue = queues_.find(id);
  if (queue == queues_.end()) return;
  for (const Waiting& w : queue->second.messages) queued_bytes_ -= w.message.frameBytes();
  queues_.erase(queue);
}

void SendQueues::dropFront(Queue& queue) {
  queued_bytes_ -= queue.messages.front().message.frameBytes();
  queue.messages.pop_front();
  ++queue.new_drops;
  ++total_drops_;
}

SendQueues::Queue* SendQueues::oldestExcept(std::uint64_t keep) {
  Queue* oldest = nullptr;
  for (auto& [id, queue] : queues_) {
    if (queue.messages.empty() || queue.messages.front().order == keep) continue;
    if (!oldest || queue.messages.front().order < oldest->messages.front().order) oldest = &queue;
  }
  return oldest;
}

bool SendQueues::push(QueuedMessage message, std::size_t socket_bytes) {
  const auto found = queues_.find(message.subscription);
  if (found == queues_.end()) return false;
  Queue& queue = found->second;
  const std::uint64_t order = next_order_++;
  queued_bytes_ += message.frameBytes();
  queue.messages.push_back({std::move(message), order});
  while (queue.messages.size() > queue.depth) dropFront(queue);
  while (queued_bytes_ + socket_bytes > max_bytes_) {
    Queue* oldest = oldestExcept(order);
    if (!oldest) break;  // only this message is left: it goes, however large
    dropFront(*oldest);
  }
  return true;
}

std::optional<QueuedMessage> SendQueues::takeFront(std::map<SubscriptionId, Queue>::iterator queue) {
  QueuedMessage message = std::move(queue->second.messages.front().message);
  queue->second.messages.pop_front();
  queued_bytes_ -= message.frameBytes();
  next_turn_ = queue->first + 1;  // wraps to 0 past the largest id, which lower_bound handles
  return message;
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
  for (const auto& [id, queue] : queues_) n += queue.messages.size();
  return n;
}

}  // namespace uampc::foxglove
