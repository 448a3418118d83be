#include "uampc/recording/playback.hpp"

#include <algorithm>
#include <stdexcept>

namespace uampc::recording {

namespace {

// How far ahead of what is due the file is read, in log time: one window's samples are held in
// memory (about 10 scans of a Mid-360 a second), and a sample received up to this long after it
// was published still goes out in order.
const Time kReadWindow = Time::fromSeconds(1.0);

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

Playback::Playback(const std::string& path, const std::vector<std::string>& topics) : path_(path) {
  try {
    reader_ = std::make_unique<mcap::Reader>(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("cannot read the recording: ") + e.what());
  }
  warnings_ = reader_->warnings();
  std::vector<std::string> recorded;
  for (const auto& channel : reader_->channels()) recorded.push_back(channel.topic);
  topic_names_ = topics.empty() ? recorded : topics;
  bool clock_known = false;
  for (const std::string& name : topic_names_) {
    const mcap::Channel* channel = reader_->findChannel(name);
    if (!channel)
      throw std::runtime_error(path + ": the recording has no topic " + name + " (it has: " + join(recorded) + ")");
    if (channel->message_encoding != "cdr") {
      throw std::runtime_error(path + ": topic " + name + " is recorded as '" + channel->message_encoding +
                               "', not as CDR: uampc plays ROS 2 recordings only");
    }
    const auto schema = std::find_if(reader_->schemas().begin(), reader_->schemas().end(),
                                     [&](const mcap::Schema& s) { return s.id == channel->schema_id; });
    if (schema == reader_->schemas().end() || schema->encoding != "ros2msg" || schema->name.empty()) {
      throw std::runtime_error(path + ": topic " + name + " has no ros2msg schema, so its type is unknown");
    }
    RecordedTopic topic{name, schema->name, qosFromMetadata(channel->metadata).value_or(QosPreset::kControl)};
    topic_by_channel_[channel->id] = topics_.size();
    topics_.push_back(topic);
    // One clock for the whole recording: uampc's recorder writes it on every channel.
    if (!clock_known) {
      clock_ = clockFromMetadata(channel->metadata).value_or(RecordingClock::kRealtime);
      clock_known = true;
    }
  }
  const Time first_log{static_cast<std::int64_t>(reader_->startTime())};
  end_ = Time{static_cast<std::int64_t>(reader_->endTime())};
  sample_count_ = reader_->messageCount();
  // The start is the first sample's due time; a lockstep recording's samples are due when they
  // were published, before they were logged (latched ones at 0).
  read_to_ = first_log;
  readAhead(first_log);
  start_ = first_log;
  for (const auto& sample : pending_) start_ = std::min(start_, sample.time);
}

void Playback::readAhead(Time until) {
  while (read_to_ <= until && read_to_ <= end_) {
    const Time window_end = read_to_ + kReadWindow;
    reader_->forEachMessage(topic_names_, static_cast<std::uint64_t>(read_to_.ns), [&](const mcap::MessageView& m) {
      if (static_cast<std::int64_t>(m.log_time) >= window_end.ns) return false;
      const auto topic = topic_by_channel_.find(m.channel->id);
      if (topic == topic_by_channel_.end()) return true;
      RecordedSample sample;
      sample.topic = topic->second;
      sample.time = Time{static_cast<std::int64_t>(clock_ == RecordingClock::kLockstep ? m.publish_time : m.log_time)};
      sample.data.data.assign(m.data, m.data + m.size);
      pending_.push_back(std::move(sample));
      return true;
    });
    read_to_ = window_end;
  }
}

bool Playback::next(Time until, RecordedSample& sample) {
  readAhead(until + kReadWindow);
  if (pending_.empty() || pending_.front().time > until) return false;
  sample = std::move(pending_.front());
  pending_.pop_front();
  return true;
}

void Playback::rewind() {
  pending_.clear();
  read_to_ = Time{static_cast<std::int64_t>(reader_->startTime())};
}

}  // namespace uampc::recording
