#include "chunk_loader.hpp"

#include "crc32.hpp"

namespace uampc::mcap::detail {

namespace {

// The largest record read into memory at once: a chunk of the largest size decoded plus slack for
// compressed data that grew (incompressible records stored by zstd or lz4 grow by under 1 %).
constexpr std::uint64_t kMaxRecordLength = kMaxUncompressedChunk + (kMaxUncompressedChunk >> 4);

void checkDeclaredSizes(const ChunkRecord& chunk) {
  if (chunk.uncompressed_size > kMaxUncompressedChunk) {
    throw FormatError("chunk declares " + std::to_string(chunk.uncompressed_size) +
                      " uncompressed bytes, over the 1 GiB uampc reads");
  }
  if (chunk.uncompressed_size > kMaxCompressionRatio * chunk.records_size) {
    throw FormatError("chunk declares " + std::to_string(chunk.uncompressed_size) + " uncompressed bytes from " +
                      std::to_string(chunk.records_size) + " compressed, over " + std::to_string(kMaxCompressionRatio) +
                      " times as many: refused as damaged");
  }
}

void checkRecordLength(std::uint64_t length) {
  if (length > kMaxRecordLength) {
    throw FormatError("a record of " + std::to_string(length) + " bytes, over the 1 GiB uampc reads at once");
  }
}

template <typename T>
void expectEqual(const char* field, T in_record, T declared) {
  if (in_record != declared) {
    throw FormatError(std::string("chunk's ") + field + " is " + std::to_string(in_record) + " but its index says " +
                      std::to_string(declared));
  }
}

void checkAgainstLocation(const ChunkRecord& chunk, const ChunkLocation& location) {
  if (chunk.compression != location.compression) {
    throw FormatError("chunk's compression is '" + chunk.compression + "' but its index says '" + location.compression +
                      "'");
  }
  expectEqual("compressed size", chunk.records_size, location.compressed_size);
  expectEqual("uncompressed size", chunk.uncompressed_size, location.uncompressed_size);
  expectEqual("message_start_time", chunk.message_start_time, location.start_time);
  expectEqual("message_end_time", chunk.message_end_time, location.end_time);
}

}  // namespace

ChunkRecords decodeChunkRecords(const ChunkRecord& chunk, const std::shared_ptr<const Buffer>& record,
                                ChunkDecoder& decoder) {
  checkDeclaredSizes(chunk);
  ChunkRecords records;
  if (chunk.compression.empty()) {
    if (chunk.records_size != chunk.uncompressed_size) {
      throw FormatError("uncompressed chunk holds " + std::to_string(chunk.records_size) + " bytes but declares " +
                        std::to_string(chunk.uncompressed_size));
    }
    records = {record, chunk.records, static_cast<std::size_t>(chunk.records_size)};
  } else {
    const std::shared_ptr<Buffer> decompressed = decoder.decompressed_buffers.get();
    decoder.decompressor.decompress(chunk.compression, chunk.records, chunk.records_size, chunk.uncompressed_size,
                                    *decompressed);
    records = {decompressed, decompressed->data(), decompressed->size()};
  }
  if (chunk.uncompressed_crc != 0) {
    const std::uint32_t computed = crc32(records.data, records.size);
    if (computed != chunk.uncompressed_crc) {
      throw FormatError("chunk CRC mismatch: its records checksum to " + std::to_string(computed) +
                        ", the chunk declares " + std::to_string(chunk.uncompressed_crc));
    }
  }
  return records;
}

Buffer readRecord(const InputFile& file, std::uint64_t offset, std::uint64_t length) {
  checkRecordLength(length);
  return file.read(offset, length);
}

ChunkRecords loadChunk(const InputFile& file, const ChunkLocation& location, ChunkDecoder& decoder) {
  try {
    checkRecordLength(location.length);
    const std::shared_ptr<Buffer> record = decoder.read_buffers.get();
    file.read(location.offset, location.length, *record);
    if (record->size() < kRecordPrefixSize) throw FormatError("chunk record shorter than its opcode and length");
    if ((*record)[0] != static_cast<std::uint8_t>(Opcode::kChunk)) {
      throw FormatError("expected a Chunk record, found opcode " + std::to_string((*record)[0]));
    }
    const auto declared = getLittleEndian<std::uint64_t>(record->data() + 1);
    expectEqual("record length", declared, location.length - kRecordPrefixSize);
    const ChunkRecord chunk = decodeChunk(record->data() + kRecordPrefixSize, record->size() - kRecordPrefixSize);
    checkAgainstLocation(chunk, location);
    return decodeChunkRecords(chunk, record, decoder);
  } catch (const FormatError& e) {
    throw McapError(recordError(file.path(), location.offset, e.what()));
  }
}

}  // namespace uampc::mcap::detail
