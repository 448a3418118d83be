// The MCAP records uampc writes and reads (spec, "Records"), one struct per record with its
// encoder (appends the whole record: opcode, content length, content) and its decoder (takes the
// content only, throws FormatError). Fields a newer writer appends to a record are ignored, as the
// spec requires.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "byte_io.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::detail {

enum class Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
constexpr std::uint64_t kRecordPrefixSize = 9;    // opcode byte + uint64 content length
constexpr std::uint64_t kFooterContentSize = 20;  // summary_start, summary_offset_start, summary_crc
constexpr std::uint64_t kMessageHeaderSize = 22;  // channel_id, sequence, log_time, publish_time
constexpr std::uint64_t kFooterAndMagicSize = kRecordPrefixSize + kFooterContentSize + sizeof(kMagic);

struct HeaderRecord {
  std::string profile;
  std::string library;
};

struct FooterRecord {
  std::uint64_t summary_start = 0;
  std::uint64_t summary_offset_start = 0;
  std::uint32_t summary_crc = 0;
};

// A Message record's fields; `data` points into the buffer the record was decoded from.
struct MessageRecord {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// A Chunk record's fields; `records` points into the buffer the record was decoded from.
struct ChunkRecord {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string compression;
  const std::uint8_t* records = nullptr;
  std::uint64_t records_size = 0;
};

struct MessageIndexRecord {
  std::uint16_t channel_id = 0;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> entries;  // log_time, offset in the chunk's records
};

struct ChunkIndexRecord {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;  // of the whole Chunk record
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};

struct StatisticsRecord {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

struct SummaryOffsetRecord {
  Opcode group_opcode = Opcode::kSchema;
  std::uint64_t group_start = 0;
  std::uint64_t group_length = 0;
};

void encode(Bytes& out, const HeaderRecord& r);
void encode(Bytes& out, const FooterRecord& r);
void encode(Bytes& out, const Schema& r);
void encode(Bytes& out, const Channel& r);
void encode(Bytes& out, const MessageRecord& r);
void encode(Bytes& out, const ChunkRecord& r);
// The Chunk record up to its records (whose length it declares): the writer appends the
// compressed records itself rather than copying them.
void encodeChunkHead(Bytes& out, const ChunkRecord& r);
void encode(Bytes& out, const MessageIndexRecord& r);
void encode(Bytes& out, const ChunkIndexRecord& r);
void encode(Bytes& out, const StatisticsRecord& r);
void encode(Bytes& out, const SummaryOffsetRecord& r);
void encodeDataEnd(Bytes& out, std::uint32_t data_section_crc);

HeaderRecord decodeHeader(const std::uint8_t* content, std::size_t size);
FooterRecord decodeFooter(const std::uint8_t* content, std::size_t size);
Schema decodeSchema(const std::uint8_t* content, std::size_t size);
Channel decodeChannel(const std::uint8_t* content, std::size_t size);
MessageRecord decodeMessage(const std::uint8_t* content, std::size_t size);
ChunkRecord decodeChunk(const std::uint8_t* content, std::size_t size);
ChunkIndexRecord decodeChunkIndex(const std::uint8_t* content, std::size_t size);
StatisticsRecord decodeStatistics(const std::uint8_t* content, std::size_t size);

// One record of a sequence of records: `offset` is where its opcode byte is, from the start of
// the sequence.
struct RecordView {
  std::uint8_t opcode = 0;
  std::uint64_t offset = 0;
  const std::uint8_t* content = nullptr;
  std::uint64_t size = 0;
};

// Calls visit(RecordView) for each record of [data, data + size) in order; throws FormatError
// naming the offset of a record that runs past the end.
template <typename Visit>
void forEachRecord(const std::uint8_t* data, std::uint64_t size, Visit visit) {
  std::uint64_t at = 0;
  while (at < size) {
    if (size - at < kRecordPrefixSize) {
      throw FormatError("record at offset " + std::to_string(at) + " is cut off in its opcode and length");
    }
    RecordView record;
    record.opcode = data[at];
    record.offset = at;
    record.size = getLittleEndian<std::uint64_t>(data + at + 1);
    if (record.size > size - at - kRecordPrefixSize) {
      throw FormatError("record at offset " + std::to_string(at) + " declares " + std::to_string(record.size) +
                        " bytes but only " + std::to_string(size - at - kRecordPrefixSize) + " follow");
    }
    record.content = data + at + kRecordPrefixSize;
    visit(record);
    at += kRecordPrefixSize + record.size;
  }
}

}  // namespace uampc::mcap::detail
