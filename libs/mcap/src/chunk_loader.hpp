// Reading one chunk: the checks that keep a damaged or hostile file from costing unbounded memory
// (declared sizes), and those that tell a damaged chunk from a good one (sizes, CRC).
#pragma once

#include <cstdint>
#include <memory>

#include "buffer_pool.hpp"
#include "compression.hpp"
#include "file_index.hpp"
#include "file_io.hpp"
#include "records.hpp"

namespace uampc::mcap::detail {

// A chunk may declare at most this many uncompressed bytes, and at most kMaxCompressionRatio
// times its compressed size; more is refused before anything is allocated.
constexpr std::uint64_t kMaxUncompressedChunk = std::uint64_t{1} << 30;
constexpr std::uint64_t kMaxCompressionRatio = 64;

// A chunk's records, decoded: decompressed into a buffer of their own or, for an uncompressed
// chunk, where they are in the buffer the Chunk record was read into. `owner` keeps them alive.
struct ChunkRecords {
  std::shared_ptr<const Buffer> owner;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// What decoding reuses from one chunk to the next: buffers for records as read from the file and
// for records decompressed (two pools, so that a small buffer for one is not grown for the other),
// and the decompression contexts.
struct ChunkDecoder {
  BufferPool read_buffers;
  BufferPool decompressed_buffers;
  ChunkDecompressor decompressor;
};

// The records of `chunk`, decoded from `record` (the buffer holding the Chunk record), and checked
// against the chunk's CRC when it has one. Throws FormatError.
ChunkRecords decodeChunkRecords(const ChunkRecord& chunk, const std::shared_ptr<const Buffer>& record,
                                ChunkDecoder& decoder);

// Reads the Chunk record at `location`, checks it against what `location` declares, and returns its
// decoded records. Throws McapError("FILE: record at byte OFFSET: ...") with the chunk's offset.
ChunkRecords loadChunk(const InputFile& file, const ChunkLocation& location, ChunkDecoder& decoder);

// The `length` bytes at `offset`; throws FormatError when that is more than uampc reads at once.
Buffer readRecord(const InputFile& file, std::uint64_t offset, std::uint64_t length);

}  // namespace uampc::mcap::detail
