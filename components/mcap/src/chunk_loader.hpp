// Reading one chunk: the checks that keep a damaged or hostile file from costing unbounded memory
// (declared sizes), and those that tell a damaged chunk from a good one (sizes, CRC).
#pragma once

#include <cstdint>

#include "file_index.hpp"
#include "file_io.hpp"
#include "records.hpp"

namespace uampc::mcap::detail {

// A chunk may declare at most this many uncompressed bytes, and at most kMaxCompressionRatio
// times its compressed size; more is refused before anything is allocated.
constexpr std::uint64_t kMaxUncompressedChunk = std::uint64_t{1} << 30;
constexpr std::uint64_t kMaxCompressionRatio = 64;

// The chunk's records, decompressed and checked against the chunk's CRC (when it has one).
// Throws FormatError.
Bytes decodeChunkRecords(const ChunkRecord& chunk);

// Reads the Chunk record at `location`, checks it against what `location` declares, and returns its
// decoded records. Throws McapError("FILE: record at byte OFFSET: ...") with the chunk's offset.
Bytes loadChunk(const InputFile& file, const ChunkLocation& location);

// The `length` bytes at `offset`; throws FormatError when that is more than uampc reads at once.
Bytes readRecord(const InputFile& file, std::uint64_t offset, std::uint64_t length);

}  // namespace uampc::mcap::detail
