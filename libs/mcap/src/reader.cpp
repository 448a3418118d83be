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

// A k-way merge of the sources by log_time: a source is opened when the earliest message not yet
// handed out is no earlier than the source's start, so only chunks overlapping in time are in
// memory.
struct MessageStream::Merge {
  std::set<std::uint16_t> wanted;
  std::uint64_t start_ns = 0;
  std::vector<Source> sources;
  std::size_t next_source = 0;
  std::deque<Cursor> cursors;
  std::priority_queue<Cursor*, std::vector<Cursor*>, LaterFirst> heap;
  Cursor* handed_out = nullptr;  // its current message was handed out last; moved on at the next call
};

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

  std::unique_ptr<MessageStream::Merge> startMerge(const std::vector<std::string>& topics,
                                                   std::uint64_t start_ns) const {
    auto merge = std::make_unique<MessageStream::Merge>();
    merge->wanted = wantedChannels(topics);
    merge->start_ns = start_ns;
    merge->sources = sourcesFor(merge->wanted, start_ns);
    return merge;
  }

  bool next(MessageStream::Merge& m, MessageView& view) {
    if (Cursor* done = m.handed_out) {
      m.handed_out = nullptr;
      if (++done->next < done->messages.size()) {
        m.heap.push(done);
      } else {
        done->bytes.reset();  // its buffer is not needed any more
        done->messages.clear();
      }
    }
    while (m.next_source < m.sources.size() &&
           (m.heap.empty() || m.sources[m.next_source].start_time <= m.heap.top()->current().log_time)) {
      m.cursors.push_back(open(m.sources[m.next_source++], m.wanted, m.start_ns));
      if (m.cursors.back().messages.empty()) {
        m.cursors.pop_back();
      } else {
        m.heap.push(&m.cursors.back());
      }
    }
    if (m.heap.empty()) return false;
    Cursor* cursor = m.heap.top();
    m.heap.pop();
    m.handed_out = cursor;
    const MessageRecord& r = cursor->current();
    view = {&index_.channels[channel_by_id_.at(r.channel_id)], r.sequence, r.log_time, r.publish_time, r.data, r.size};
    return true;
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

  ChunkRecords chunkRecords(const ChunkLocation& chunk) { return loadChunk(file_, chunk, decoder_); }

  InputFile file_;
  FileIndex index_;
  std::unordered_map<std::uint16_t, std::size_t> channel_by_id_;
  ChunkDecoder decoder_;
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
  MessageStream stream = messages(topics, start_ns);
  MessageView view{};
  while (stream.next(view)) {
    if (!visit(view)) return;
  }
}

MessageStream Reader::messages(const std::vector<std::string>& topics, std::uint64_t start_ns) {
  return MessageStream(*impl_, impl_->startMerge(topics, start_ns));
}

MessageStream::MessageStream(Reader::Impl& reader, std::unique_ptr<Merge> merge)
    : reader_(&reader), merge_(std::move(merge)) {}
MessageStream::~MessageStream() = default;
MessageStream::MessageStream(MessageStream&&) noexcept = default;
MessageStream& MessageStream::operator=(MessageStream&&) noexcept = default;

bool MessageStream::next(MessageView& message) { return reader_->next(*merge_, message); }

}  // namespace uampc::mcap
