// What `uampc topic hz` and `uampc topic bw` measure, over a window of the latest samples, computed
// as `ros2 topic hz` and `ros2 topic bw` do so that the figures compare: the rate is one over the
// mean period between arrivals, with the periods' min, max and standard deviation; the bandwidth is
// the mean sample size times that rate. Arrival times are the tool's own (the receive time).
#pragma once

#include <cstddef>
#include <deque>
#include <string>

namespace uampc::app {

class TopicStatistics {
 public:
  explicit TopicStatistics(std::size_t window) : window_(window < 2 ? 2 : window) {}

  // A sample of `bytes` (the whole CDR payload, header included) arrived at `time_s`.
  void add(double time_s, std::size_t bytes);

  std::size_t samples() const { return times_.size(); }
  std::size_t received() const { return received_; }  // since the start, not only in the window

  // At least two samples are needed for any period.
  bool hasRate() const { return times_.size() >= 2; }
  double rateHz() const;  // 1 / mean period
  double minPeriodS() const;
  double maxPeriodS() const;
  double periodStdDevS() const;   // population standard deviation, as ros2 topic hz
  double bytesPerSecond() const;  // mean size x rate
  double meanBytes() const;
  std::size_t minBytes() const;
  std::size_t maxBytes() const;

  // "average rate: 20.000\n\tmin: 0.050s max: 0.050s std dev: 0.00012s window: 21\n"
  std::string hzReport() const;
  // "240 B/s from 20 messages\n\tMessage size mean: 12 B min: 12 B max: 12 B\n"
  std::string bwReport() const;

 private:
  double meanPeriodS() const;

  std::size_t window_;
  std::deque<double> times_;
  std::deque<std::size_t> sizes_;
  std::size_t received_ = 0;
};

// "12 B", "12.50 B", "1.23 KB", "4.56 MB" (powers of 1000, as ros2 topic bw).
std::string formatBytes(double bytes);

}  // namespace uampc::app
