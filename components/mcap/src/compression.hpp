// Chunk compression as the spec names it: "zstd" (a Zstandard frame), "lz4" (an LZ4 frame, not a
// raw LZ4 block) or "" (none), with Debian's libzstd and liblz4.
#pragma once

#include <cstdint>
#include <string>

#include "byte_io.hpp"
#include "uampc/mcap/mcap.hpp"

struct ZSTD_CCtx_s;
struct ZSTD_DCtx_s;

namespace uampc::mcap::detail {

// The value of a Chunk record's compression field.
std::string compressionName(Compression compression);

// Compresses chunks one after the other, keeping its compression context between them.
class ChunkCompressor {
 public:
  explicit ChunkCompressor(Compression compression);
  ~ChunkCompressor();
  ChunkCompressor(const ChunkCompressor&) = delete;
  ChunkCompressor& operator=(const ChunkCompressor&) = delete;

  Compression compression() const { return compression_; }
  // The compressed records: `in` itself for kNone, else a buffer of the compressor's, valid until
  // the next call.
  const Bytes& compress(const Bytes& in);

 private:
  Compression compression_;
  ZSTD_CCtx_s* zstd_ = nullptr;
  Bytes out_;
};

// Decompresses a chunk's records into exactly `uncompressed_size` bytes. Throws FormatError for an
// unknown compression, a damaged stream, or a stream that holds more or fewer bytes than declared;
// never writes or allocates beyond `uncompressed_size`.
Bytes decompress(const std::string& compression, const std::uint8_t* data, std::uint64_t size,
                 std::uint64_t uncompressed_size);

}  // namespace uampc::mcap::detail
