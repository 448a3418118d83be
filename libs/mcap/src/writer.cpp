#include <algorithm>
#include <atomic>
#include <iostream>
#include <limits>
#include <memory>

#include "chunk_builder.hpp"
#include "chunk_hand_off.hpp"
#include "chunk_loader.hpp"
#include "compression.hpp"
#include "crc32.hpp"
#include "file_io.hpp"
#include "records.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap {

using namespace detail;

class Writer::Impl {
 public:
  Impl(const std::string& path, WriterOptions options)
      : file_(path), options_(std::move(options)), compressor_(options_.compression) {
    file_.write(kMagic, sizeof(kMagic));
    Bytes header;
    encode(header, HeaderRecord{options_.profile, options_.library});
    file_.write(header);
    bytes_written_ = file_.bytesWritten();
    if (options_.background) {
      hand_off_ = std::make_unique<ChunkHandOff>([this](const ChunkBuilder& chunk) { storeChunk(chunk); });
    }
  }

  std::uint16_t addSchema(const std::string& name, const std::string& encoding, const std::string& data) {
    checkOpen();
    schemas_.push_back(Schema{nextId(schemas_.size(), "schemas"), name, encoding, data});
    return schemas_.back().id;
  }

  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata) {
    checkOpen();
    if (schema_id > schemas_.size()) {
      throw McapError(file_.path() + ": channel " + topic + " names schema " + std::to_string(schema_id) +
                      ", which was not added");
    }
    channels_.push_back(Channel{nextId(channels_.size(), "channels"), schema_id, topic, message_encoding, metadata});
    channel_message_counts_[channels_.back().id] = 0;
    return channels_.back().id;
  }

  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time, std::uint64_t publish_time,
             const std::uint8_t* data, std::size_t size) {
    checkOpen();
    if (channel_id == 0 || channel_id > channels_.size()) {
      throw McapError(file_.path() + ": a message on channel " + std::to_string(channel_id) + ", which was not added");
    }
    const Channel& channel = channels_[channel_id - 1];
    const Schema* schema = channel.schema_id == 0 ? nullptr : &schemas_[channel.schema_id - 1];
    chunk_.addMessage(schema, channel, MessageRecord{channel_id, sequence, log_time, publish_time, data, size});
    countMessage(channel_id, log_time);
    if (chunk_.size() >= options_.chunk_size) writeChunk();
  }

  void close() {
    if (closed_) return;
    closed_ = true;  // a failure below is reported once, not again by the destructor
    writeChunk();
    if (hand_off_) hand_off_->finish();
    Bytes tail;
    encodeDataEnd(tail, 0);  // 0: no data section CRC (as rosbag2 writes)
    file_.write(tail);
    writeSummaryAndFooter();
    file_.close();
    bytes_written_ = file_.bytesWritten();
  }

  std::uint64_t bytesWritten() const { return bytes_written_; }
  bool closed() const { return closed_; }
  const std::string& path() const { return file_.path(); }

 private:
  void checkOpen() const {
    if (closed_) throw McapError(file_.path() + ": the writer is closed");
  }

  std::uint16_t nextId(std::size_t count, const char* what) const {
    if (count >= std::numeric_limits<std::uint16_t>::max()) {
      throw McapError(file_.path() + ": more than 65535 " + what + " (MCAP ids are 16 bits)");
    }
    return static_cast<std::uint16_t>(count + 1);
  }

  void countMessage(std::uint16_t channel_id, std::uint64_t log_time) {
    statistics_.message_start_time =
        statistics_.message_count == 0 ? log_time : std::min(statistics_.message_start_time, log_time);
    statistics_.message_end_time = std::max(statistics_.message_end_time, log_time);
    ++statistics_.message_count;
    ++channel_message_counts_[channel_id];
  }

  // The chunk being filled goes to the file, or to the worker that stores it; either way chunk_ is
  // then empty.
  void writeChunk() {
    if (chunk_.empty()) return;
    if (hand_off_) return hand_off_->handOver(chunk_);
    storeChunk(chunk_);
    chunk_.clear();
  }

  // Chunk record (compressed records), then one Message Index record per channel in it. On the
  // worker thread when options_.background: it alone touches file_, compressor_ and chunk_indexes_
  // until close() has joined it.
  void storeChunk(const ChunkBuilder& full) {
    const Bytes& records = full.records();
    ByteView stored;
    try {
      stored = compressor_.compress(records);
    } catch (const FormatError& e) {
      throw McapError(file_.path() + ": " + e.what());
    }
    std::string compression = compressionName(compressor_.compression());
    // The reader refuses a chunk that declares more than kMaxCompressionRatio times its compressed
    // size (a decompression bomb, or a damaged size field); a chunk that compresses that far
    // (records of zeros) is stored uncompressed instead, so that every file we write is one we read.
    if (stored.data != records.data() && stored.size * kMaxCompressionRatio < records.size()) {
      stored = {records.data(), records.size()};
      compression.clear();
    }
    ChunkRecord chunk;
    chunk.message_start_time = full.startTime();
    chunk.message_end_time = full.endTime();
    chunk.uncompressed_size = records.size();
    chunk.uncompressed_crc = crc32(records.data(), records.size());
    chunk.compression = compression;
    chunk.records_size = stored.size;

    ChunkIndexRecord index;
    index.message_start_time = chunk.message_start_time;
    index.message_end_time = chunk.message_end_time;
    index.chunk_start_offset = file_.bytesWritten();
    index.compression = compression;
    index.compressed_size = stored.size;
    index.uncompressed_size = records.size();

    Bytes head;
    encodeChunkHead(head, chunk);
    file_.write(head);
    file_.write(stored.data, stored.size);
    index.chunk_length = file_.bytesWritten() - index.chunk_start_offset;

    Bytes message_indexes;
    for (const auto& [channel_id, entries] : full.messageIndex()) {
      index.message_index_offsets[channel_id] = file_.bytesWritten() + message_indexes.size();
      MessageIndexRecord message_index{channel_id, entries};
      std::stable_sort(message_index.entries.begin(), message_index.entries.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      encode(message_indexes, message_index);
    }
    file_.write(message_indexes);
    index.message_index_length = message_indexes.size();
    file_.flush();  // a recorder killed from here on leaves this chunk readable

    chunk_indexes_.push_back(std::move(index));
    bytes_written_ = file_.bytesWritten();
  }

  // Summary (groups of Schema, Channel, Statistics, Chunk Index records), one Summary Offset record
  // per group, Footer, magic. The footer's CRC covers the summary up to its own CRC field.
  void writeSummaryAndFooter() {
    const std::uint64_t summary_start = file_.bytesWritten();
    Bytes summary;
    std::vector<SummaryOffsetRecord> groups;
    auto group = [&](Opcode opcode, auto&& encodeRecords) {
      const std::size_t begin = summary.size();
      encodeRecords();
      if (summary.size() > begin) groups.push_back({opcode, summary_start + begin, summary.size() - begin});
    };
    group(Opcode::kSchema, [&] {
      for (const Schema& s : schemas_) encode(summary, s);
    });
    group(Opcode::kChannel, [&] {
      for (const Channel& c : channels_) encode(summary, c);
    });
    group(Opcode::kStatistics, [&] { encode(summary, statistics()); });
    group(Opcode::kChunkIndex, [&] {
      for (const ChunkIndexRecord& c : chunk_indexes_) encode(summary, c);
    });

    const std::uint64_t summary_offset_start = summary_start + summary.size();
    for (const SummaryOffsetRecord& g : groups) encode(summary, g);

    FooterRecord footer{summary_start, summary_offset_start, 0};
    Bytes footer_bytes;
    encode(footer_bytes, footer);
    Crc32 crc;
    crc.update(summary.data(), summary.size());
    crc.update(footer_bytes.data(), footer_bytes.size() - 4);  // up to, not including, summary_crc
    footer.summary_crc = crc.value();
    footer_bytes.clear();
    encode(footer_bytes, footer);

    file_.write(summary);
    file_.write(footer_bytes);
    file_.write(kMagic, sizeof(kMagic));
  }

  StatisticsRecord statistics() const {
    StatisticsRecord s = statistics_;
    s.schema_count = static_cast<std::uint16_t>(schemas_.size());
    s.channel_count = static_cast<std::uint32_t>(channels_.size());
    s.chunk_count = static_cast<std::uint32_t>(chunk_indexes_.size());
    s.channel_message_counts = channel_message_counts_;
    return s;
  }

  OutputFile file_;
  WriterOptions options_;
  ChunkCompressor compressor_;
  std::vector<Schema> schemas_;    // schemas_[id - 1]
  std::vector<Channel> channels_;  // channels_[id - 1]
  ChunkBuilder chunk_;
  std::vector<ChunkIndexRecord> chunk_indexes_;
  StatisticsRecord statistics_;  // message count and time range; the rest is filled in at close
  std::map<std::uint16_t, std::uint64_t> channel_message_counts_;
  bool closed_ = false;
  std::atomic<std::uint64_t> bytes_written_ = 0;  // read by any thread while the worker writes
  std::unique_ptr<ChunkHandOff> hand_off_;        // last: stopped before what its worker uses goes
};

Writer::Writer(const std::string& path, WriterOptions options)
    : impl_(std::make_unique<Impl>(path, std::move(options))) {}

namespace {

void closeQuietly(Writer& writer, bool open) {
  if (!open) return;
  try {
    writer.close();
  } catch (const std::exception& e) {
    std::cerr << "uampc mcap: " << e.what() << '\n';
  }
}

}  // namespace

Writer::~Writer() { closeQuietly(*this, impl_ && !impl_->closed()); }

Writer::Writer(Writer&&) noexcept = default;

Writer& Writer::operator=(Writer&& other) noexcept {
  if (this != &other) {
    closeQuietly(*this, impl_ && !impl_->closed());
    impl_ = std::move(other.impl_);
  }
  return *this;
}

std::uint16_t Writer::addSchema(const std::string& name, const std::string& encoding, const std::string& data) {
  return impl_->addSchema(name, encoding, data);
}

std::uint16_t Writer::addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                 const std::map<std::string, std::string>& metadata) {
  return impl_->addChannel(schema_id, topic, message_encoding, metadata);
}

void Writer::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                   std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size) {
  impl_->write(channel_id, sequence, log_time_ns, publish_time_ns, data, size);
}

void Writer::close() { impl_->close(); }

std::uint64_t Writer::bytesWritten() const { return impl_->bytesWritten(); }

}  // namespace uampc::mcap
