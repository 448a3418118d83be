// MCAP files (https://mcap.dev/spec) as rosbag2 writes them: the container of `uampc record` and
// `uampc play`. No DDS here: schemas, channels and messages are plain strings and bytes; the
// recording library decides what they mean (ros2msg definitions, CDR samples).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace uampc::mcap {

// Every error of this library: a message naming the file, and the byte offset of the record when
// the file is bad ("FILE: record at byte OFFSET: what is wrong").
class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Compression { kNone, kZstd, kLz4 };

struct WriterOptions {
  Compression compression = Compression::kZstd;
  std::uint64_t chunk_size = 4 * 1024 * 1024;  // bytes of uncompressed records per chunk
  std::string profile = "ros2";
  std::string library;  // e.g. "uampc 0.3.0"; written in the Header record
  // Compress and store full chunks on a worker thread (write() then only copies the message into
  // the chunk). The file is the same byte for byte; an error of the worker is thrown by the next
  // write() or by close(), and a process killed loses the chunks still queued (at most two).
  bool background = false;
};

struct Schema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;
  std::string data;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  // 0: no schema
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
};

// A message as forEachMessage and MessageStream hand it out: `data` is valid during the visit
// (until the stream's next call) only.
struct MessageView {
  const Channel* channel;
  std::uint32_t sequence;
  std::uint64_t log_time;
  std::uint64_t publish_time;
  const std::uint8_t* data;
  std::size_t size;
};

// Writes Header, then chunks (each followed by its message indexes), then on close() DataEnd, the
// summary (schemas, channels, statistics, chunk indexes), summary offsets and the footer.
// Throws McapError naming the file on any I/O error.
class Writer {
 public:
  Writer(const std::string& path, WriterOptions options);
  ~Writer();  // calls close(); an error there is printed to stderr (a destructor cannot throw)
  Writer(Writer&&) noexcept;
  Writer& operator=(Writer&&) noexcept;
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Ids are handed out from 1 (0 means "no schema" to a channel).
  std::uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data);
  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata = {});
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             const std::uint8_t* data, std::size_t size);
  // Last chunk, DataEnd, summary, summary offsets, footer, magic. Idempotent.
  void close();
  std::uint64_t bytesWritten() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// Reads a file through its summary when the footer and summary are valid; otherwise (a recorder
// killed before close(), a damaged summary) by scanning the data section, keeping every complete
// chunk whose CRC is right up to the first truncated or corrupt record (recovered(), warnings()).
// Throws McapError("FILE: record at byte OFFSET: what is wrong") on bad input.
class MessageStream;

class Reader {
 public:
  explicit Reader(const std::string& path);
  ~Reader();
  Reader(Reader&&) noexcept;
  Reader& operator=(Reader&&) noexcept;
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  const std::vector<Schema>& schemas() const;
  const std::vector<Channel>& channels() const;
  const Channel* findChannel(const std::string& topic) const;  // nullptr: no such topic
  std::uint64_t messageCount() const;
  std::uint64_t startTime() const;  // earliest log_time, 0 without messages
  std::uint64_t endTime() const;    // latest log_time, 0 without messages
  // True: no valid summary/footer (e.g. recorder killed); the file was read by scanning.
  bool recovered() const;
  // What was skipped or why the file was scanned, one sentence each, naming file and byte offset.
  const std::vector<std::string>& warnings() const;

  // Messages in log_time order (ties: file order), only the given topics (empty: all), from
  // start_ns. `visit` returns false to stop.
  void forEachMessage(const std::vector<std::string>& topics, std::uint64_t start_ns,
                      const std::function<bool(const MessageView&)>& visit);
  // The same messages, pulled one at a time: a player goes through a long file once, holding only
  // the chunks that overlap in time. The stream uses this reader, which must outlive it.
  MessageStream messages(const std::vector<std::string>& topics, std::uint64_t start_ns);

 private:
  friend class MessageStream;
  class Impl;
  std::unique_ptr<Impl> impl_;
};

class MessageStream {
 public:
  ~MessageStream();
  MessageStream(MessageStream&&) noexcept;
  MessageStream& operator=(MessageStream&&) noexcept;
  // The next message, false at the end. Throws McapError for a damaged chunk on the way.
  bool next(MessageView& message);

 private:
  friend class Reader;
  struct Merge;
  MessageStream(Reader::Impl& reader, std::unique_ptr<Merge> merge);
  Reader::Impl* reader_;
  std::unique_ptr<Merge> merge_;
};

}  // namespace uampc::mcap
