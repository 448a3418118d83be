// Writes a run's samples to an MCAP file as rosbag2 does (profile ros2, schemas as ros2msg
// definitions, messages as CDR): used by the recorder component and by `uampc record`.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "uampc/mcap/mcap.hpp"
#include "uampc/recording/recorded_topic.hpp"
#include "uampc/runtime/serialized_message.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc::recording {

struct RecordingOptions {
  mcap::Compression compression = mcap::Compression::kZstd;
  std::uint64_t chunk_size = 4 * 1024 * 1024;  // bytes of records before a chunk is compressed
  RecordingClock clock = RecordingClock::kLockstep;
};

// "zstd", "lz4", "none"; throws std::invalid_argument for anything else.
mcap::Compression compressionByName(const std::string& name);

class RecordingWriter {
 public:
  // Throws std::runtime_error naming the file when it cannot be written.
  RecordingWriter(const std::string& path, const RecordingOptions& options);

  // Returns the handle write() takes. A type this process does not know (no message package
  // registered it) is recorded with an empty definition: its samples are kept, but tools that
  // decode need the definition; `unknown_type` is set so that the caller can say so.
  std::size_t addTopic(const RecordedTopic& topic, bool* unknown_type = nullptr);

  // log_time: when the sample was received; published: when its writer published it.
  void write(std::size_t topic, Time log_time, Time published, const SerializedMessage& sample);
  void close();

  std::uint64_t messages() const { return messages_; }
  const std::string& path() const { return path_; }

 private:
  struct Channel {
    std::uint16_t id = 0;
    std::uint32_t sequence = 0;
  };
  std::string path_;
  RecordingOptions options_;
  mcap::Writer writer_;
  std::map<std::string, std::uint16_t> schema_by_type_;
  std::vector<Channel> channels_;
  std::uint64_t messages_ = 0;
};

}  // namespace uampc::recording
