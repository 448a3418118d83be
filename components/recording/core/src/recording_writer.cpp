#include "uampc/recording/recording_writer.hpp"

#include <stdexcept>

#include "uampc/runtime/message_type.hpp"

namespace uampc::recording {

namespace {

constexpr char kSchemaEncoding[] = "ros2msg";
constexpr char kMessageEncoding[] = "cdr";

// MCAP times are unsigned nanoseconds; a time before the epoch (impossible from our clocks) would
// wrap, so it is refused.
std::uint64_t mcapTime(Time t) {
  if (t.ns < 0) throw std::runtime_error("cannot record a sample stamped before time 0");
  return static_cast<std::uint64_t>(t.ns);
}

mcap::WriterOptions writerOptions(const RecordingOptions& options) {
  mcap::WriterOptions w;
  w.compression = options.compression;
  w.chunk_size = options.chunk_size;
  w.profile = "ros2";
  w.library = "uampc";
  // Compression and the file write on their own thread: the recorder's part of a running system's
  // step is then only copying the sample (docs/results/recording-cost.md).
  w.background = true;
  return w;
}

}  // namespace

mcap::Compression compressionByName(const std::string& name) {
  if (name == "zstd") return mcap::Compression::kZstd;
  if (name == "lz4") return mcap::Compression::kLz4;
  if (name == "none") return mcap::Compression::kNone;
  throw std::invalid_argument("unknown compression '" + name + "' (zstd, lz4 or none)");
}

RecordingWriter::RecordingWriter(const std::string& path, const RecordingOptions& options)
    : path_(path), options_(options), writer_(path, writerOptions(options)) {}

std::size_t RecordingWriter::addTopic(const RecordedTopic& topic, bool* unknown_type) {
  auto schema = schema_by_type_.find(topic.type);
  if (schema == schema_by_type_.end()) {
    std::string definition;
    try {
      definition = messageDefinition(topic.type);
    } catch (const std::runtime_error&) {
      // IDL outside the subset the definition parser reads (a user's union, say): the samples
      // are kept all the same, as for a type not known at all.
    }
    if (unknown_type) *unknown_type = definition.empty();
    schema = schema_by_type_.emplace(topic.type, writer_.addSchema(topic.type, kSchemaEncoding, definition)).first;
  } else if (unknown_type) {
    *unknown_type = false;
  }
  const std::uint16_t id =
      writer_.addChannel(schema->second, topic.topic, kMessageEncoding, channelMetadata(topic, options_.clock));
  channels_.push_back({id, 0});
  return channels_.size() - 1;
}

void RecordingWriter::write(std::size_t topic, Time log_time, Time published, const SerializedMessage& sample) {
  Channel& channel = channels_.at(topic);
  writer_.write(channel.id, channel.sequence++, mcapTime(log_time), mcapTime(published), sample.data.data(),
                sample.data.size());
  ++messages_;
}

void RecordingWriter::close() { writer_.close(); }

}  // namespace uampc::recording
