#include "chunk_hand_off.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <utility>

namespace uampc::mcap::detail {

ChunkHandOff::ChunkHandOff(std::function<void(const ChunkBuilder&)> store)
    : store_(std::move(store)), worker_([this] { work(); }) {}

ChunkHandOff::~ChunkHandOff() {
  try {
    finish();
  } catch (...) {  // sticky: the owner saw it at its last handOver() or finish()
  }
}

void ChunkHandOff::handOver(ChunkBuilder& full) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return queued_.size() < kChunksInFlight || failure_; });
  rethrowFailure();
  queued_.push_back(std::move(full));
  if (spare_.empty()) {
    full = ChunkBuilder();
  } else {
    full = std::move(spare_.back());
    spare_.pop_back();
  }
  changed_.notify_all();
}

void ChunkHandOff::finish() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    changed_.notify_all();
  }
  if (worker_.joinable()) worker_.join();
  std::lock_guard lock(mutex_);
  rethrowFailure();
}

void ChunkHandOff::rethrowFailure() {
  if (failure_) std::rethrow_exception(failure_);
}

// The worker runs at the lowest priority (nice 19; on Linux a thread has its own): a lockstep step
// is a chain of wake-ups between processes, and a chunk compressed at normal priority delays
// them whenever it holds the core one of them wakes on (measured on 2 cores: the recording cost
// 17 % of the real-time factor at nice 0, 11 % at nice 19). It is never starved: a full queue
// stops the writer until the worker has caught up. If the call fails, it works at normal priority.
void ChunkHandOff::work() {
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return !queued_.empty() || stopping_; });
    if (queued_.empty()) return;  // stopping, and every chunk is stored
    ChunkBuilder chunk = std::move(queued_.front());
    lock.unlock();
    std::exception_ptr failure;
    try {
      store_(chunk);
    } catch (...) {
      failure = std::current_exception();
    }
    chunk.clear();
    lock.lock();
    queued_.pop_front();
    spare_.push_back(std::move(chunk));
    if (failure) {
      failure_ = failure;
      queued_.clear();
    }
    changed_.notify_all();
    if (failure_) return;
  }
}

}  // namespace uampc::mcap::detail
