#include "topic/topic_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace uampc::app {

void TopicStatistics::add(double time_s, std::size_t bytes) {
  times_.push_back(time_s);
  sizes_.push_back(bytes);
  ++received_;
  while (times_.size() > window_) {
    times_.pop_front();
    sizes_.pop_front();
  }
}

double TopicStatistics::meanPeriodS() const {
  return (times_.back() - times_.front()) / static_cast<double>(times_.size() - 1);
}

double TopicStatistics::rateHz() const { return 1.0 / meanPeriodS(); }

double TopicStatistics::minPeriodS() const {
  double shortest = times_[1] - times_[0];
  for (std::size_t i = 2; i < times_.size(); ++i) shortest = std::min(shortest, times_[i] - times_[i - 1]);
  return shortest;
}

double TopicStatistics::maxPeriodS() const {
  double longest = times_[1] - times_[0];
  for (std::size_t i = 2; i < times_.size(); ++i) longest = std::max(longest, times_[i] - times_[i - 1]);
  return longest;
}

double TopicStatistics::periodStdDevS() const {
  const double mean = meanPeriodS();
  double sum_of_squares = 0.0;
  for (std::size_t i = 1; i < times_.size(); ++i) {
    const double d = times_[i] - times_[i - 1] - mean;
    sum_of_squares += d * d;
  }
  return std::sqrt(sum_of_squares / static_cast<double>(times_.size() - 1));
}

double TopicStatistics::meanBytes() const {
  double total = 0.0;
  for (std::size_t s : sizes_) total += static_cast<double>(s);
  return total / static_cast<double>(sizes_.size());
}

std::size_t TopicStatistics::minBytes() const { return *std::min_element(sizes_.begin(), sizes_.end()); }
std::size_t TopicStatistics::maxBytes() const { return *std::max_element(sizes_.begin(), sizes_.end()); }

double TopicStatistics::bytesPerSecond() const { return meanBytes() * rateHz(); }

std::string TopicStatistics::hzReport() const {
  char text[200];
  std::snprintf(text, sizeof text, "average rate: %.3f\n\tmin: %.3fs max: %.3fs std dev: %.5fs window: %zu\n", rateHz(),
                minPeriodS(), maxPeriodS(), periodStdDevS(), times_.size());
  return text;
}

std::string TopicStatistics::bwReport() const {
  return formatBytes(bytesPerSecond()) + "/s from " + std::to_string(sizes_.size()) +
         " messages\n\tMessage size mean: " + formatBytes(meanBytes()) +
         " min: " + formatBytes(static_cast<double>(minBytes())) +
         " max: " + formatBytes(static_cast<double>(maxBytes())) + "\n";
}

std::string formatBytes(double bytes) {
  char text[64];
  if (bytes < 1000.0) {
    if (bytes == std::floor(bytes)) {
      std::snprintf(text, sizeof text, "%.0f B", bytes);
    } else {
      std::snprintf(text, sizeof text, "%.2f B", bytes);
    }
  } else if (bytes < 1e6) {
    std::snprintf(text, sizeof text, "%.2f KB", bytes / 1e3);
  } else {
    std::snprintf(text, sizeof text, "%.2f MB", bytes / 1e6);
  }
  return text;
}

}  // namespace uampc::app
