#include "file_index.hpp"

#include <algorithm>
#include <tuple>

#include "chunk_loader.hpp"
#include "crc32.hpp"

namespace uampc::mcap::detail {

namespace {

// A summary the reader cannot use: it scans the data section instead and says why.
class SummaryUnusable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RecordPrefix {
  std::uint8_t opcode = 0;
  std::uint64_t length = 0;  // of the content
};

RecordPrefix readPrefix(const InputFile& file, std::uint64_t offset) {
  const Buffer prefix = file.read(offset, kRecordPrefixSize);
  return {prefix[0], getLittleEndian<std::uint64_t>(prefix.data() + 1)};
}

bool isMagic(const std::uint8_t* bytes) { return std::equal(kMagic, kMagic + sizeof(kMagic), bytes); }

// Magic, then the Header record; returns the offset of the data section.
std::uint64_t readMagicAndHeader(const InputFile& file, HeaderRecord& header) {
  if (file.size() == 0) throw McapError(file.path() + ": empty file, not an MCAP file");
  if (file.size() < sizeof(kMagic) || !isMagic(file.read(0, sizeof(kMagic)).data())) {
    throw McapError(file.path() + ": not an MCAP file (it does not start with the MCAP magic bytes)");
  }
  const std::uint64_t at = sizeof(kMagic);
  if (file.size() - at < kRecordPrefixSize)
    throw McapError(recordError(file.path(), at, "the Header record is cut off"));
  const RecordPrefix prefix = readPrefix(file, at);
  if (prefix.opcode != static_cast<std::uint8_t>(Opcode::kHeader)) {
    throw McapError(
        recordError(file.path(), at, "expected the Header record, found opcode " + std::to_string(prefix.opcode)));
  }
  if (prefix.length > file.size() - at - kRecordPrefixSize) {
    throw McapError(recordError(
        file.path(), at,
        "the Header record declares " + std::to_string(prefix.length) + " bytes, more than the file holds after it"));
  }
  try {
    const Buffer content = readRecord(file, at + kRecordPrefixSize, prefix.length);
    header = decodeHeader(content.data(), content.size());
  } catch (const FormatError& e) {
    throw McapError(recordError(file.path(), at, e.what()));
  }
  return at + kRecordPrefixSize + prefix.length;
}

bool sameDefinition(const Schema& a, const Schema& b) {
  return std::tie(a.name, a.encoding, a.data) == std::tie(b.name, b.encoding, b.data);
}

bool sameDefinition(const Channel& a, const Channel& b) {
  return std::tie(a.schema_id, a.topic, a.message_encoding, a.metadata) ==
         std::tie(b.schema_id, b.topic, b.message_encoding, b.metadata);
}

// Adds a schema or channel met in the file; the same id twice must mean the same thing.
template <typename T>
void addDefinition(std::vector<T>& known, const T& added, const char* what) {
  const auto same_id = std::find_if(known.begin(), known.end(), [&](const T& k) { return k.id == added.id; });
  if (same_id == known.end()) {
    known.push_back(added);
  } else if (!sameDefinition(*same_id, added)) {
    throw FormatError(std::string(what) + " " + std::to_string(added.id) + " is defined twice, differently");
  }
}

// The schemas and channels known at a point of the file.
struct Definitions {
  std::vector<Schema> schemas;
  std::vector<Channel> channels;

  bool knowsChannel(std::uint16_t id) const {
    return std::any_of(channels.begin(), channels.end(), [&](const Channel& c) { return c.id == id; });
  }
  bool knowsSchema(std::uint16_t id) const {
    return std::any_of(schemas.begin(), schemas.end(), [&](const Schema& s) { return s.id == id; });
  }
  void add(const Schema& schema) { addDefinition(schemas, schema, "schema"); }
  void add(const Channel& channel);
};

void Definitions::add(const Channel& channel) {
  const bool schema_known = channel.schema_id == 0 || knowsSchema(channel.schema_id);
  if (!schema_known) {
    throw FormatError("channel " + std::to_string(channel.id) + " (" + channel.topic + ") names schema " +
                      std::to_string(channel.schema_id) + ", which is not defined before it");
  }
  addDefinition(channels, channel, "channel");
}

// ---- The summary ----

struct Summary {
  Definitions definitions;
  std::vector<ChunkIndexRecord> chunk_indexes;
  bool has_statistics = false;
  StatisticsRecord statistics;
};

FooterRecord readFooter(const InputFile& file, std::uint64_t data_start) {
  if (file.size() < data_start + kFooterAndMagicSize) throw SummaryUnusable("the file ends before a footer");
  const std::uint64_t footer_offset = file.size() - kFooterAndMagicSize;
  const Buffer tail = file.read(footer_offset, kFooterAndMagicSize);
  if (!isMagic(tail.data() + tail.size() - sizeof(kMagic))) {
    throw SummaryUnusable("no MCAP magic at its end (the writer did not finish)");
  }
  if (tail[0] != static_cast<std::uint8_t>(Opcode::kFooter) ||
      getLittleEndian<std::uint64_t>(tail.data() + 1) != kFooterContentSize) {
    throw SummaryUnusable("no Footer record before its closing magic");
  }
  return decodeFooter(tail.data() + kRecordPrefixSize, kFooterContentSize);
}

void collectSummaryRecord(const RecordView& record, Summary& summary) {
  switch (static_cast<Opcode>(record.opcode)) {
    case Opcode::kSchema:
      summary.definitions.add(decodeSchema(record.content, record.size));
      break;
    case Opcode::kChannel:
      summary.definitions.add(decodeChannel(record.content, record.size));
      break;
    case Opcode::kChunkIndex:
      summary.chunk_indexes.push_back(decodeChunkIndex(record.content, record.size));
      break;
    case Opcode::kStatistics:
      summary.statistics = decodeStatistics(record.content, record.size);
      summary.has_statistics = true;
      break;
    default:  // attachment and metadata indexes, and opcodes newer than this reader
      break;
  }
}

Summary readSummaryRecords(const InputFile& file, std::uint64_t data_start, const FooterRecord& footer) {
  const std::uint64_t footer_offset = file.size() - kFooterAndMagicSize;
  if (footer.summary_start == 0) throw SummaryUnusable("it has no summary section");
  const std::uint64_t records_end = footer.summary_offset_start != 0 ? footer.summary_offset_start : footer_offset;
  if (footer.summary_start < data_start || footer.summary_start > records_end || records_end > footer_offset) {
    throw SummaryUnusable("its footer points outside the file");
  }
  // The CRC covers the summary and summary offsets up to the footer's own summary_crc field.
  Buffer summary;
  try {
    summary = readRecord(file, footer.summary_start, footer_offset + kRecordPrefixSize + 16 - footer.summary_start);
  } catch (const FormatError& e) {
    throw SummaryUnusable(std::string("its summary is too large to read (") + e.what() + ")");
  }
  if (footer.summary_crc != 0 && crc32(summary.data(), summary.size()) != footer.summary_crc) {
    throw SummaryUnusable("its summary does not match the footer's CRC");
  }
  Summary result;
  try {
    forEachRecord(summary.data(), records_end - footer.summary_start,
                  [&](const RecordView& record) { collectSummaryRecord(record, result); });
  } catch (const FormatError& e) {
    throw SummaryUnusable(std::string("its summary does not decode (") + e.what() + ")");
  }
  return result;
}

ChunkLocation locationOf(const ChunkIndexRecord& index) {
  ChunkLocation location;
  location.offset = index.chunk_start_offset;
  location.length = index.chunk_length;
  location.start_time = index.message_start_time;
  location.end_time = index.message_end_time;
  location.compressed_size = index.compressed_size;
  location.uncompressed_size = index.uncompressed_size;
  location.compression = index.compression;
  for (const auto& entry : index.message_index_offsets) location.channels.insert(entry.first);
  return location;
}

// The summary is used only when it describes every message: statistics with as many chunks as it
// has chunk indexes, each pointing into the data section, on channels it defines.
void useSummary(const Summary& summary, std::uint64_t data_start, std::uint64_t summary_start, FileIndex& index) {
  if (!summary.has_statistics) throw SummaryUnusable("its summary has no Statistics record");
  if (summary.statistics.chunk_count != summary.chunk_indexes.size()) {
    throw SummaryUnusable("its summary counts " + std::to_string(summary.statistics.chunk_count) +
                          " chunks but indexes " + std::to_string(summary.chunk_indexes.size()));
  }
  for (const ChunkIndexRecord& chunk : summary.chunk_indexes) {
    const bool inside = chunk.chunk_start_offset >= data_start && chunk.chunk_start_offset <= summary_start &&
                        chunk.chunk_length >= kRecordPrefixSize &&
                        chunk.chunk_length <= summary_start - chunk.chunk_start_offset;
    if (!inside) throw SummaryUnusable("a chunk index points outside the data section");
    for (const auto& entry : chunk.message_index_offsets) {
      if (!summary.definitions.knowsChannel(entry.first)) {
        throw SummaryUnusable("a chunk index names channel " + std::to_string(entry.first) +
                              ", which it does not define");
      }
    }
    index.chunks.push_back(locationOf(chunk));
  }
  index.schemas = summary.definitions.schemas;
  index.channels = summary.definitions.channels;
  index.message_count = summary.statistics.message_count;
  index.start_time = summary.statistics.message_start_time;
  index.end_time = summary.statistics.message_end_time;
}

// ---- Scanning the data section ----

// What the scan has learnt so far; a chunk adds to it only when all of it decodes.
struct ScanState {
  Definitions definitions;
  std::vector<ChunkLocation> chunks;
  std::vector<LooseMessage> loose_messages;
  std::uint64_t message_count = 0;
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;

  void count(std::uint64_t messages, std::uint64_t first, std::uint64_t last) {
    if (messages == 0) return;
    start_time = message_count == 0 ? first : std::min(start_time, first);
    end_time = message_count == 0 ? last : std::max(end_time, last);
    message_count += messages;
  }
  void count(std::uint64_t log_time) { count(1, log_time, log_time); }
  void check(const MessageRecord& message) const {
    if (!definitions.knowsChannel(message.channel_id)) {
      throw FormatError("a message on channel " + std::to_string(message.channel_id) +
                        ", which is not defined before it");
    }
  }
};

// Decodes the whole chunk (so that its CRC is checked) and learns the schemas and channels it
// defines. Nothing of it is kept if any of it is wrong.
void scanChunk(const std::shared_ptr<const Buffer>& record, std::uint64_t offset, ScanState& state,
               ChunkDecoder& decoder) {
  const ChunkRecord chunk = decodeChunk(record->data() + kRecordPrefixSize, record->size() - kRecordPrefixSize);
  const ChunkRecords records = decodeChunkRecords(chunk, record, decoder);
  ScanState updated;
  updated.definitions = state.definitions;
  ChunkLocation location;
  location.offset = offset;
  location.length = record->size();
  location.start_time = chunk.message_start_time;
  location.end_time = chunk.message_end_time;
  location.compressed_size = chunk.records_size;
  location.uncompressed_size = chunk.uncompressed_size;
  location.compression = chunk.compression;
  forEachRecord(records.data, records.size, [&](const RecordView& r) {
    switch (static_cast<Opcode>(r.opcode)) {
      case Opcode::kSchema:
        updated.definitions.add(decodeSchema(r.content, r.size));
        break;
      case Opcode::kChannel:
        updated.definitions.add(decodeChannel(r.content, r.size));
        break;
      case Opcode::kMessage: {
        const MessageRecord message = decodeMessage(r.content, r.size);
        updated.check(message);
        if (message.log_time < chunk.message_start_time || message.log_time > chunk.message_end_time) {
          throw FormatError("a message's log_time is outside the chunk's declared time range");
        }
        location.channels.insert(message.channel_id);
        updated.count(message.log_time);
        break;
      }
      default:
        break;
    }
  });
  state.definitions = std::move(updated.definitions);
  state.chunks.push_back(location);
  state.count(updated.message_count, updated.start_time, updated.end_time);
}

// Acts on one complete record of the data section; returns false at its end (Data End).
bool scanRecord(const InputFile& file, std::uint64_t at, const RecordPrefix& prefix, ScanState& state,
                ChunkDecoder& decoder) {
  const auto opcode = static_cast<Opcode>(prefix.opcode);
  switch (opcode) {
    case Opcode::kDataEnd:
    case Opcode::kFooter:
      return false;
    case Opcode::kChunk:
      scanChunk(std::make_shared<const Buffer>(readRecord(file, at, kRecordPrefixSize + prefix.length)), at, state,
                decoder);
      return true;
    case Opcode::kSchema:
    case Opcode::kChannel:
    case Opcode::kMessage:
      break;
    default:  // message indexes, attachments, metadata, opcodes newer than this reader
      return true;
  }
  const Buffer record = readRecord(file, at, kRecordPrefixSize + prefix.length);
  const std::uint8_t* content = record.data() + kRecordPrefixSize;
  if (opcode == Opcode::kSchema) state.definitions.add(decodeSchema(content, prefix.length));
  if (opcode == Opcode::kChannel) state.definitions.add(decodeChannel(content, prefix.length));
  if (opcode == Opcode::kMessage) {
    const MessageRecord message = decodeMessage(content, prefix.length);
    state.check(message);
    state.loose_messages.push_back({at, record.size(), message.log_time, message.channel_id});
    state.count(message.log_time);
  }
  return true;
}

// Reads records from the start of the data section up to Data End, or up to the first record that
// is cut off or damaged: what comes before it is kept, the rest is lost, and a warning says where.
void scanDataSection(const InputFile& file, std::uint64_t data_start, FileIndex& index) {
  ScanState state;
  ChunkDecoder decoder;
  const auto stop = [&](std::uint64_t at, const std::string& what) {
    index.warnings.push_back(
        recordError(file.path(), at,
                    what + "; the " + std::to_string(state.chunks.size()) + " complete chunks before it are read"));
  };
  std::uint64_t at = data_start;
  while (true) {
    if (file.size() - at < kRecordPrefixSize) {
      stop(at, at == file.size() ? "the file ends without a Data End record" : "a record cut off in its length");
      break;
    }
    const RecordPrefix prefix = readPrefix(file, at);
    if (prefix.length > file.size() - at - kRecordPrefixSize) {
      stop(at, "a record (opcode " + std::to_string(prefix.opcode) + ") declares " + std::to_string(prefix.length) +
                   " bytes but the file ends " + std::to_string(file.size() - at - kRecordPrefixSize) +
                   " bytes after its length: cut off");
      break;
    }
    try {
      if (!scanRecord(file, at, prefix, state, decoder)) break;
    } catch (const FormatError& e) {
      stop(at, std::string("damaged: ") + e.what());
      break;
    }
    at += kRecordPrefixSize + prefix.length;
  }
  index.schemas = std::move(state.definitions.schemas);
  index.channels = std::move(state.definitions.channels);
  index.chunks = std::move(state.chunks);
  index.loose_messages = std::move(state.loose_messages);
  index.message_count = state.message_count;
  index.start_time = state.start_time;
  index.end_time = state.end_time;
}

}  // namespace

FileIndex indexFile(const InputFile& file) {
  FileIndex index;
  const std::uint64_t data_start = readMagicAndHeader(file, index.header);
  try {
    const FooterRecord footer = readFooter(file, data_start);
    useSummary(readSummaryRecords(file, data_start, footer), data_start, footer.summary_start, index);
    return index;
  } catch (const SummaryUnusable& why) {
    const HeaderRecord header = index.header;
    index = FileIndex{};
    index.header = header;
    index.recovered = true;
    index.warnings.push_back(file.path() + ": " + why.what() + "; reading its data section record by record");
  }
  scanDataSection(file, data_start, index);
  return index;
}

}  // namespace uampc::mcap::detail
