// Hands full chunks from the thread that writes messages to one worker thread that compresses and
// stores them (WriterOptions::background). Writing a message then costs a copy into the chunk;
// the CRC, the compression and the file write, most of a recorder's work, run beside it, on
// another core where there is one, as rosbag2's recorder does with its cache consumer thread.
// At most kChunksInFlight full chunks wait: a writer that outpaces the disk waits for it, and
// the memory stays bounded. The builders are recycled, so their buffers are allocated (and
// page-faulted in) once.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "chunk_builder.hpp"

namespace uampc::mcap::detail {

class ChunkHandOff {
 public:
  static constexpr std::size_t kChunksInFlight = 2;

  // `store` runs on the worker thread, one chunk at a time, in the order the chunks were handed.
  explicit ChunkHandOff(std::function<void(const ChunkBuilder&)> store);
  ~ChunkHandOff();  // finish() without reporting its error
  ChunkHandOff(const ChunkHandOff&) = delete;
  ChunkHandOff& operator=(const ChunkHandOff&) = delete;

  // Queues `full` (it becomes an empty builder to fill next). Rethrows the error of an earlier
  // store(), at every call from then on: after one, no chunk is stored any more.
  void handOver(ChunkBuilder& full);
  // Waits until every queued chunk is stored and stops the worker; rethrows store()'s error.
  void finish();

 private:
  void work();
  void rethrowFailure();

  std::function<void(const ChunkBuilder&)> store_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<ChunkBuilder> queued_;
  std::vector<ChunkBuilder> spare_;
  bool stopping_ = false;
  std::exception_ptr failure_;
  std::thread worker_;
};

}  // namespace uampc::mcap::detail
