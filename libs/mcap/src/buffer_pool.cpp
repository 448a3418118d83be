#include "buffer_pool.hpp"

namespace uampc::mcap::detail {

BufferPool::BufferPool(std::size_t keep) : idle_(std::make_shared<Idle>(Idle{keep, {}})) {}

std::shared_ptr<Buffer> BufferPool::get() {
  std::unique_ptr<Buffer> buffer;
  if (idle_->buffers.empty()) {
    buffer = std::make_unique<Buffer>();
  } else {
    buffer = std::move(idle_->buffers.back());
    idle_->buffers.pop_back();
  }
  buffer->clear();
  const std::weak_ptr<Idle> pool = idle_;
  return std::shared_ptr<Buffer>(buffer.release(), [pool](Buffer* b) {
    std::unique_ptr<Buffer> owned(b);
    const auto idle = pool.lock();
    if (idle && idle->buffers.size() < idle->keep) idle->buffers.push_back(std::move(owned));
  });
}

}  // namespace uampc::mcap::detail
