// Wakes a waiting thread when data arrives on any DDS reader it listens to.
#pragma once

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>

namespace uampc {

class Wakeup : public eprosima::fastdds::dds::DataReaderListener {
 public:
  void on_data_available(eprosima::fastdds::dds::DataReader*) override { notify(); }
  void notify() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_ = true;
    }
    cv_.notify_one();
  }
  // Waits until data arrived or the deadline passed; returns true if data arrived.
  bool waitUntil(std::chrono::steady_clock::time_point deadline) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait_until(lock, deadline, [this] { return pending_; });
    const bool had = pending_;
    pending_ = false;
    return had;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool pending_ = false;
};

// The listener of one DDS reader: wakes the process's Wakeup and remembers that the reader got
// data, so that a poll skips readers that got nothing. A take costs Fast DDS calls even on an empty
// reader (Debian's build runs its debug checks), and most readers are empty at most 5 ms steps.
class ReaderActivity : public eprosima::fastdds::dds::DataReaderListener {
 public:
  explicit ReaderActivity(Wakeup& wakeup) : wakeup_(wakeup) {}
  void on_data_available(eprosima::fastdds::dds::DataReader*) override {
    pending_.store(true);
    wakeup_.notify();
  }
  // Whether data arrived since the last call; clears the mark. Call it before taking: a sample that
  // arrives during the takes marks the reader again, so none is left behind.
  bool takeMark() { return pending_.exchange(false); }

 private:
  Wakeup& wakeup_;
  std::atomic<bool> pending_{true};  // the first poll looks whatever happened before
};

}  // namespace uampc
