#include "uampc/recording/playback.hpp"

#include <algorithm>
#include <stdexcept>

#include "uampc/runtime/lockstep_topics.hpp"

namespace uampc::recording {

namespace {

// How far ahead of what is due the file is read, in log time: about a second of samples is held in
// memory (10 scans of a Mid-360), and a sample received up to this long after it was published
// still goes out in order.
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
  bool clock_known = false;
  for (const std::string& name : topics.empty() ? recorded : topics) {
    if (isLockstepRunTopic(name)) {
      // A lockstep run's own topics: a live run on the domain would take them for another run's
      // (docs/decisions/replay-leaves-lockstep-topics.md).
      skipped_.push_back(name);
      continue;
    }
    topic_names_.push_back(name);
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
  seek(first_log);
  readAhead(first_log + kReadWindow);
  start_ = first_log;
  for (const auto& sample : pending_) start_ = std::min(start_, sample.time);
}

void Playback::readAhead(Time until) {
  mcap::MessageView m{};
  while (!exhausted_ && read_to_ <= until) {
    if (!stream_->next(m)) {
      exhausted_ = true;
      return;
    }
    const auto topic = topic_by_channel_.find(m.channel->id);
    if (topic == topic_by_channel_.end()) continue;
    RecordedSample sample;
    sample.topic = topic->second;
    sample.time = dueTime(m);
    sample.data.data.assign(m.data, m.data + m.size);
    read_to_ = Time{static_cast<std::int64_t>(m.log_time)};
    // Due times may be out of log order (a lockstep sample delivered late); ties keep file order.
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), sample.time,
                                     [](Time t, const RecordedSample& s) { return t < s.time; });
    pending_.insert(at, std::move(sample));
  }
}

Time Playback::dueTime(const mcap::MessageView& message) const {
  return Time{static_cast<std::int64_t>(clock_ == RecordingClock::kLockstep ? message.publish_time : message.log_time)};
}

std::uint64_t Playback::samplesDueFrom(Time from) {
  std::uint64_t count = 0;
  // From `from`'s log time, as seek() reads; a lockstep sample logged after `from` but published
  // before it is read there and not played, so it is not counted either.
  reader_->forEachMessage(topic_names_, static_cast<std::uint64_t>(std::max<std::int64_t>(from.ns, 0)),
                          [&](const mcap::MessageView& m) {
                            if (topic_by_channel_.count(m.channel->id) && dueTime(m) >= from) ++count;
                            return true;
                          });
  return count;
}

bool Playback::next(Time until, RecordedSample& sample) {
  readAhead(until + kReadWindow);
  if (pending_.empty() || pending_.front().time > until) return false;
  sample = std::move(pending_.front());
  pending_.pop_front();
  return true;
}

void Playback::seek(Time time) {
  pending_.clear();
  exhausted_ = false;
  read_to_ = time;
  stream_.emplace(reader_->messages(topic_names_, static_cast<std::uint64_t>(std::max<std::int64_t>(time.ns, 0))));
}

}  // namespace uampc::recording
