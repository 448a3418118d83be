#include <algorithm>
#include <deque>
#include <memory>
#include <queue>
#include <set>
#include <unordered_map>

#include "buffer_pool.hpp"
#include "chunk_loader.hpp"
#include "file_index.hpp"
#include "file_io.hpp"
#include "records.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap {

using namespace detail;

namespace {

// Decoded chunks kept between calls of forEachMessage: a player reads a window at a time, and the
// chunk at a window's edge is then decompressed once, not once per window (four chunks of the
// default size).
constexpr std::uint64_t kChunkCacheBytes = 16 * 1024 * 1024;

// Where messages come from: a chunk, or one Message record outside any chunk.
struct Source {
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::uint64_t file_offset = 0;
  const ChunkLocation* chunk = nullptr;  // either this
  const LooseMessage* loose = nullptr;   // or this
};

// The wanted messages of one source in (log_time, file order), handed out one at a time; holds
// the decoded bytes they point into.
struct Cursor {
  std::shared_ptr<const Buffer> bytes;
  std::vector<MessageRecord> messages;
  std::size_t next = 0;
  std::uint64_t file_offset = 0;

  const MessageRecord& current() const { return messages[next]; }
};

// Orders the merge: earliest log_time first, ties in file order (the sources' offsets; within a
// source, the cursor keeps file order).
struct LaterFirst {
  bool operator()(const Cursor* a, const Cursor* b) const {
    const MessageRecord& x = a->current();
    const MessageRecord& y = b->current();
    if (x.log_time != y.log_time) return x.log_time > y.log_time;
    return a->file_offset > b->file_offset;  // a cursor is in the heap once, so offsets differ
  }
};

}  // namespace

class Reader::Impl {
 public:
  explicit Impl(const std::string& path) : file_(path), index_(indexFile(file_)) {
    for (std::size_t i = 0; i < index_.channels.size(); ++i) channel_by_id_[index_.channels[i].id] = i;
  }

  const FileIndex& index() const { return index_; }

  const Channel* findChannel(const std::string& topic) const {
    const auto found = std::find_if(index_.channels.begin(), index_.channels.end(),
                                    [&](const Channel& c) { return c.topic == topic; });
    return found == index_.channels.end() ? nullptr : &*found;
  }

  // A k-way merge of the sources by log_time: a source is opened when the earliest message not yet
  // visited is no earlier than the source's start, so only chunks overlapping in time are in memory.
  void forEachMessage(const std::vector<std::string>& topics, std::uint64_t start_ns,
                      const std::function<bool(const MessageView&)>& visit) {
    const std::set<std::uint16_t> wanted = wantedChannels(topics);
    const std::vector<Source> sources = sourcesFor(wanted, start_ns);
    std::deque<Cursor> cursors;
    std::priority_queue<Cursor*, std::vector<Cursor*>, LaterFirst> heap;
    std::size_t next_source = 0;
    while (true) {
      while (next_source < sources.size() &&
             (heap.empty() || sources[next_source].start_time <= heap.top()->current().log_time)) {
        cursors.push_back(open(sources[next_source++], wanted, start_ns));
        if (cursors.back().messages.empty()) {
          cursors.pop_back();
        } else {
          heap.push(&cursors.back());
        }
      }
      if (heap.empty()) return;
      Cursor* cursor = heap.top();
      heap.pop();
      const MessageRecord& m = cursor->current();
      const MessageView view{
          &index_.channels[channel_by_id_.at(m.channel_id)], m.sequence, m.log_time, m.publish_time, m.data, m.size};
      if (!visit(view)) return;
      if (++cursor->next < cursor->messages.size()) {
        heap.push(cursor);
      } else {
        cursor->bytes.reset();  // its buffer is not needed any more
        cursor->messages.clear();
      }
    }
  }

 private:
  std::set<std::uint16_t> wantedChannels(const std::vector<std::string>& topics) const {
    std::set<std::uint16_t> wanted;
    for (const Channel& c : index_.channels) {
      if (topics.empty() || std::find(topics.begin(), topics.end(), c.topic) != topics.end()) wanted.insert(c.id);
    }
    return wanted;
  }

  // Sources that may hold a wanted message at or after start_ns, by start time then file order.
  std::vector<Source> sourcesFor(const std::set<std::uint16_t>& wanted, std::uint64_t start_ns) const {
    std::vector<Source> sources;
    if (wanted.empty()) return sources;
    for (const ChunkLocation& chunk : index_.chunks) {
      const bool has_wanted =
          chunk.channels.empty() || std::any_of(chunk.channels.begin(), chunk.channels.end(),
                                                [&](std::uint16_t id) { return wanted.count(id) > 0; });
      if (chunk.end_time >= start_ns && has_wanted)
        sources.push_back({chunk.start_time, chunk.end_time, chunk.offset, &chunk, nullptr});
    }
    for (const LooseMessage& loose : index_.loose_messages) {
      if (loose.log_time >= start_ns && wanted.count(loose.channel_id) > 0)
        sources.push_back({loose.log_time, loose.log_time, loose.offset, nullptr, &loose});
    }
    std::sort(sources.begin(), sources.end(), [](const Source& a, const Source& b) {
      return a.start_time != b.start_time ? a.start_time < b.start_time : a.file_offset < b.file_offset;
    });
    return sources;
  }

  Cursor open(const Source& source, const std::set<std::uint16_t>& wanted, std::uint64_t start_ns) {
    Cursor cursor;
    cursor.file_offset = source.file_offset;
    if (source.loose) {
      auto record = std::make_shared<const Buffer>(readRecord(source.loose->offset, source.loose->length));
      cursor.bytes = record;
      cursor.messages.push_back(
          decodeAt(record->data() + kRecordPrefixSize, record->size() - kRecordPrefixSize, source.loose->offset));
      return cursor;
    }
    const ChunkRecords records = chunkRecords(*source.chunk);
    cursor.bytes = records.owner;
    try {
      forEachRecord(records.data, records.size, [&](const RecordView& r) {
        if (r.opcode != static_cast<std::uint8_t>(Opcode::kMessage)) return;
        const MessageRecord m = decodeMessage(r.content, r.size);
        if (channel_by_id_.count(m.channel_id) == 0) {
          throw FormatError("a message on channel " + std::to_string(m.channel_id) +
                            ", which the file does not define");
        }
        if (m.log_time < source.start_time || m.log_time > source.end_time) {
          throw FormatError("a message's log_time is outside the chunk's declared time range");
        }
        if (m.log_time >= start_ns && wanted.count(m.channel_id) > 0) cursor.messages.push_back(m);
      });
    } catch (const FormatError& e) {
      throw McapError(recordError(file_.path(), source.file_offset, e.what()));
    }
    std::stable_sort(cursor.messages.begin(), cursor.messages.end(),
                     [](const MessageRecord& a, const MessageRecord& b) { return a.log_time < b.log_time; });
    return cursor;
  }

  Buffer readRecord(std::uint64_t offset, std::uint64_t length) const {
    try {
      return detail::readRecord(file_, offset, length);
    } catch (const FormatError& e) {
      throw McapError(recordError(file_.path(), offset, e.what()));
    }
  }

  MessageRecord decodeAt(const std::uint8_t* content, std::size_t size, std::uint64_t offset) const {
    try {
      return decodeMessage(content, size);
    } catch (const FormatError& e) {
      throw McapError(recordError(file_.path(), offset, e.what()));
    }
  }

  ChunkRecords chunkRecords(const ChunkLocation& chunk) {
    for (const auto& [offset, records] : cache_) {
      if (offset == chunk.offset) return records;
    }
    const ChunkRecords records = loadChunk(file_, chunk, decoder_);
    cache_.emplace_back(chunk.offset, records);
    cached_bytes_ += records.owner->size();
    while (cached_bytes_ > kChunkCacheBytes && cache_.size() > 1) {
      cached_bytes_ -= cache_.front().second.owner->size();
      cache_.pop_front();
    }
    return records;
  }

  InputFile file_;
  FileIndex index_;
  std::unordered_map<std::uint16_t, std::size_t> channel_by_id_;
  ChunkDecoder decoder_;  // before cache_, whose buffers go back to it when the reader is destroyed
  std::deque<std::pair<std::uint64_t, ChunkRecords>> cache_;  // by chunk offset, oldest first
  std::uint64_t cached_bytes_ = 0;
};

Reader::Reader(const std::string& path) : impl_(std::make_unique<Impl>(path)) {}
Reader::~Reader() = default;
Reader::Reader(Reader&&) noexcept = default;
Reader& Reader::operator=(Reader&&) noexcept = default;

const std::vector<Schema>& Reader::schemas() const { return impl_->index().schemas; }
const std::vector<Channel>& Reader::channels() const { return impl_->index().channels; }
const Channel* Reader::findChannel(const std::string& topic) const { return impl_->findChannel(topic); }
std::uint64_t Reader::messageCount() const { return impl_->index().message_count; }
std::uint64_t Reader::startTime() const { return impl_->index().start_time; }
std::uint64_t Reader::endTime() const { return impl_->index().end_time; }
bool Reader::recovered() const { return impl_->index().recovered; }
const std::vector<std::string>& Reader::warnings() const { return impl_->index().warnings; }

void Reader::forEachMessage(const std::vector<std::string>& topics, std::uint64_t start_ns,
                            const std::function<bool(const MessageView&)>& visit) {
  impl_->forEachMessage(topics, start_ns, visit);
}

}  // namespace uampc::mcap
