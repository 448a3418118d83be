// Wakes a waiting thread when data arrives on any DDS reader it listens to.
#pragma once

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

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

}  // namespace uampc
