// Reads a recording back for a player (the player component and `uampc play`): which topics it
// has, and its samples in time order, pulled from one pass over the file (mcap::MessageStream) a
// little ahead of what is due, so that a long recording is never held in memory.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "uampc/mcap/mcap.hpp"
#include "uampc/recording/recorded_topic.hpp"
#include "uampc/runtime/serialized_message.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc::recording {

struct RecordedSample {
  std::size_t topic = 0;  // index in Playback::topics()
  Time time;              // when it is due, on the recording's time line (see Playback::time)
  SerializedMessage data;
};

class Playback {
 public:
  // topics: those to play (empty: every topic of the recording), less /clock and the lockstep
  // protocol's topics, which are never played (skipped() names those left out). Throws std::runtime_error naming
  // the file for a file that is not a readable recording, a topic it lacks (listing those it has),
  // and a topic whose samples are not CDR of a ros2msg type.
  Playback(const std::string& path, const std::vector<std::string>& topics);

  const std::vector<RecordedTopic>& topics() const { return topics_; }
  // The recording's topics (or those asked for) that a lockstep run writes itself and a player
  // therefore never publishes (uampc/runtime/lockstep_topics.hpp, isLockstepRunTopic).
  const std::vector<std::string>& skipped() const { return skipped_; }
  // Lockstep recordings are played by publish time: each sample goes out in the step its original
  // writer published it, so that a lockstep scene sees every sample in the same step as the run
  // that was recorded. Others by log (receive) time, as rosbag2 plays.
  RecordingClock clock() const { return clock_; }
  Time start() const { return start_; }  // the first sample's time
  Time end() const { return end_; }      // the last sample's
  std::uint64_t sampleCount() const { return sample_count_; }  // the whole recording's, every topic
  // How many samples next() will give from a seek(from) on: those of topics() due at or after
  // `from`, which is what a player announces (sampleCount() also holds the topics it does not
  // play). One pass over the file, apart from the playing one.
  std::uint64_t samplesDueFrom(Time from);
  // Complete chunks read from a damaged file (a recorder that was killed); empty when it was whole.
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The next sample due at or before `until`, in time order; false when none is (yet).
  bool next(Time until, RecordedSample& sample);
  bool finished() const { return exhausted_ && pending_.empty(); }
  // Goes to the samples logged at or after `time` (a player's start, or the start again for a
  // loop), without reading those before.
  void seek(Time time);

 private:
  void readAhead(Time until);
  Time dueTime(const mcap::MessageView& message) const;

  std::string path_;
  std::unique_ptr<mcap::Reader> reader_;
  std::vector<RecordedTopic> topics_;
  std::vector<std::string> topic_names_;
  std::vector<std::string> skipped_;
  std::map<std::uint16_t, std::size_t> topic_by_channel_;
  RecordingClock clock_ = RecordingClock::kRealtime;
  Time start_, end_;
  std::uint64_t sample_count_ = 0;
  std::vector<std::string> warnings_;
  std::optional<mcap::MessageStream> stream_;
  bool exhausted_ = false;
  Time read_to_;                        // the log time of the last sample read into pending_
  std::deque<RecordedSample> pending_;  // by due time, ties in file order
};

}  // namespace uampc::recording
