#include "records.hpp"

namespace uampc::mcap::detail {

namespace {

// Opens a record in `out` (opcode, placeholder length) and fills in its content length when the
// object goes out of scope, so that encoders write fields straight into the output.
class RecordScope {
 public:
  RecordScope(Bytes& out, Opcode opcode) : out_(out), length_at_(out.size() + 1) {
    putU8(out_, static_cast<std::uint8_t>(opcode));
    putU64(out_, 0);
  }
  ~RecordScope() {
    const std::uint64_t length = out_.size() - length_at_ - 8;
    for (std::size_t i = 0; i < 8; ++i) out_[length_at_ + i] = static_cast<std::uint8_t>(length >> (8 * i));
  }
  RecordScope(const RecordScope&) = delete;
  RecordScope& operator=(const RecordScope&) = delete;

 private:
  Bytes& out_;
  std::size_t length_at_;
};

void putCountMap(Bytes& out, const std::map<std::uint16_t, std::uint64_t>& map) {
  LengthPrefix prefix(out);
  for (const auto& [key, value] : map) {
    putU16(out, key);
    putU64(out, value);
  }
}

std::map<std::uint16_t, std::uint64_t> getCountMap(ByteCursor& cursor, const char* field) {
  ByteCursor entries = cursor.prefixed(field);
  std::map<std::uint16_t, std::uint64_t> map;
  while (!entries.atEnd()) {
    const std::uint16_t key = entries.u16(field);
    map[key] = entries.u64(field);
  }
  return map;
}

}  // namespace

void encode(Bytes& out, const HeaderRecord& r) {
  RecordScope record(out, Opcode::kHeader);
  putString(out, r.profile);
  putString(out, r.library);
}

void encode(Bytes& out, const FooterRecord& r) {
  RecordScope record(out, Opcode::kFooter);
  putU64(out, r.summary_start);
  putU64(out, r.summary_offset_start);
  putU32(out, r.summary_crc);
}

void encode(Bytes& out, const Schema& r) {
  RecordScope record(out, Opcode::kSchema);
  putU16(out, r.id);
  putString(out, r.name);
  putString(out, r.encoding);
  putString(out, r.data);  // uint32-length-prefixed bytes: the same layout as a string
}

void encode(Bytes& out, const Channel& r) {
  RecordScope record(out, Opcode::kChannel);
  putU16(out, r.id);
  putU16(out, r.schema_id);
  putString(out, r.topic);
  putString(out, r.message_encoding);
  LengthPrefix metadata(out);
  for (const auto& [key, value] : r.metadata) {
    putString(out, key);
    putString(out, value);
  }
}

void encode(Bytes& out, const MessageRecord& r) {
  RecordScope record(out, Opcode::kMessage);
  putU16(out, r.channel_id);
  putU32(out, r.sequence);
  putU64(out, r.log_time);
  putU64(out, r.publish_time);
  putBytes(out, r.data, r.size);
}

void encodeChunkHead(Bytes& out, const ChunkRecord& r) {
  const std::uint64_t content_size = 8 + 8 + 8 + 4 + 4 + r.compression.size() + 8 + r.records_size;
  putU8(out, static_cast<std::uint8_t>(Opcode::kChunk));
  putU64(out, content_size);
  putU64(out, r.message_start_time);
  putU64(out, r.message_end_time);
  putU64(out, r.uncompressed_size);
  putU32(out, r.uncompressed_crc);
  putString(out, r.compression);
  putU64(out, r.records_size);
}

void encode(Bytes& out, const ChunkRecord& r) {
  encodeChunkHead(out, r);
  putBytes(out, r.records, r.records_size);
}

void encode(Bytes& out, const MessageIndexRecord& r) {
  RecordScope record(out, Opcode::kMessageIndex);
  putU16(out, r.channel_id);
  LengthPrefix entries(out);
  for (const auto& [log_time, offset] : r.entries) {
    putU64(out, log_time);
    putU64(out, offset);
  }
}

void encode(Bytes& out, const ChunkIndexRecord& r) {
  RecordScope record(out, Opcode::kChunkIndex);
  putU64(out, r.message_start_time);
  putU64(out, r.message_end_time);
  putU64(out, r.chunk_start_offset);
  putU64(out, r.chunk_length);
  putCountMap(out, r.message_index_offsets);
  putU64(out, r.message_index_length);
  putString(out, r.compression);
  putU64(out, r.compressed_size);
  putU64(out, r.uncompressed_size);
}

void encode(Bytes& out, const StatisticsRecord& r) {
  RecordScope record(out, Opcode::kStatistics);
  putU64(out, r.message_count);
  putU16(out, r.schema_count);
  putU32(out, r.channel_count);
  putU32(out, r.attachment_count);
  putU32(out, r.metadata_count);
  putU32(out, r.chunk_count);
  putU64(out, r.message_start_time);
  putU64(out, r.message_end_time);
  putCountMap(out, r.channel_message_counts);
}

void encode(Bytes& out, const SummaryOffsetRecord& r) {
  RecordScope record(out, Opcode::kSummaryOffset);
  putU8(out, static_cast<std::uint8_t>(r.group_opcode));
  putU64(out, r.group_start);
  putU64(out, r.group_length);
}

void encodeDataEnd(Bytes& out, std::uint32_t data_section_crc) {
  RecordScope record(out, Opcode::kDataEnd);
  putU32(out, data_section_crc);
}

HeaderRecord decodeHeader(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  HeaderRecord r;
  r.profile = c.string("profile");
  r.library = c.string("library");
  return r;
}

FooterRecord decodeFooter(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  FooterRecord r;
  r.summary_start = c.u64("summary_start");
  r.summary_offset_start = c.u64("summary_offset_start");
  r.summary_crc = c.u32("summary_crc");
  return r;
}

Schema decodeSchema(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  Schema r;
  r.id = c.u16("schema id");
  r.name = c.string("schema name");
  r.encoding = c.string("schema encoding");
  r.data = c.string("schema data");
  return r;
}

Channel decodeChannel(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  Channel r;
  r.id = c.u16("channel id");
  r.schema_id = c.u16("channel schema_id");
  r.topic = c.string("channel topic");
  r.message_encoding = c.string("channel message_encoding");
  ByteCursor metadata = c.prefixed("channel metadata");
  while (!metadata.atEnd()) {
    std::string key = metadata.string("channel metadata key");
    r.metadata[key] = metadata.string("channel metadata value");
  }
  return r;
}

MessageRecord decodeMessage(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  MessageRecord r;
  r.channel_id = c.u16("message channel_id");
  r.sequence = c.u32("message sequence");
  r.log_time = c.u64("message log_time");
  r.publish_time = c.u64("message publish_time");
  r.size = c.remaining();
  r.data = c.bytes(r.size, "message data");
  return r;
}

ChunkRecord decodeChunk(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  ChunkRecord r;
  r.message_start_time = c.u64("chunk message_start_time");
  r.message_end_time = c.u64("chunk message_end_time");
  r.uncompressed_size = c.u64("chunk uncompressed_size");
  r.uncompressed_crc = c.u32("chunk uncompressed_crc");
  r.compression = c.string("chunk compression");
  r.records_size = c.u64("chunk records length");
  r.records = c.bytes(r.records_size, "chunk records");
  return r;
}

ChunkIndexRecord decodeChunkIndex(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  ChunkIndexRecord r;
  r.message_start_time = c.u64("chunk index message_start_time");
  r.message_end_time = c.u64("chunk index message_end_time");
  r.chunk_start_offset = c.u64("chunk index chunk_start_offset");
  r.chunk_length = c.u64("chunk index chunk_length");
  r.message_index_offsets = getCountMap(c, "chunk index message_index_offsets");
  r.message_index_length = c.u64("chunk index message_index_length");
  r.compression = c.string("chunk index compression");
  r.compressed_size = c.u64("chunk index compressed_size");
  r.uncompressed_size = c.u64("chunk index uncompressed_size");
  return r;
}

StatisticsRecord decodeStatistics(const std::uint8_t* content, std::size_t size) {
  ByteCursor c(content, size);
  StatisticsRecord r;
  r.message_count = c.u64("statistics message_count");
  r.schema_count = c.u16("statistics schema_count");
  r.channel_count = c.u32("statistics channel_count");
  r.attachment_count = c.u32("statistics attachment_count");
  r.metadata_count = c.u32("statistics metadata_count");
  r.chunk_count = c.u32("statistics chunk_count");
  r.message_start_time = c.u64("statistics message_start_time");
  r.message_end_time = c.u64("statistics message_end_time");
  r.channel_message_counts = getCountMap(c, "statistics channel_message_counts");
  return r;
}

}  // namespace uampc::mcap::detail
