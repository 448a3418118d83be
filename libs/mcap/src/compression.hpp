// Chunk compression as the spec names it: "zstd" (a Zstandard frame), "lz4" (an LZ4 frame, not a
// raw LZ4 block) or "" (none), with Debian's libzstd and liblz4. Compressor and decompressor keep
// their contexts from one chunk to the next: a fresh LZ4 context allocates (and page-faults in)
// buffers of the 4 MiB block size every time.
#pragma once

#include <cstdint>
#include <string>

#include "byte_io.hpp"
#include "uampc/mcap/mcap.hpp"

struct ZSTD_CCtx_s;
struct ZSTD_DCtx_s;
struct LZ4F_cctx_s;
struct LZ4F_dctx_s;

namespace uampc::mcap::detail {

// The value of a Chunk record's compression field.
std::string compressionName(Compression compression);

class ChunkCompressor {
 public:
  explicit ChunkCompressor(Compression compression);
  ~ChunkCompressor();
  ChunkCompressor(const ChunkCompressor&) = delete;
  ChunkCompressor& operator=(const ChunkCompressor&) = delete;

  Compression compression() const { return compression_; }
  // The compressed records: `in` itself for kNone, else a buffer of the compressor's, valid until
  // the next call. Throws FormatError.
  ByteView compress(const Bytes& in);

 private:
  ByteView compressLz4(const Bytes& in);

  Compression compression_;
  ZSTD_CCtx_s* zstd_ = nullptr;
  LZ4F_cctx_s* lz4_ = nullptr;
  Buffer out_;
};

class ChunkDecompressor {
 public:
  ChunkDecompressor();
  ~ChunkDecompressor();
  ChunkDecompressor(const ChunkDecompressor&) = delete;
  ChunkDecompressor& operator=(const ChunkDecompressor&) = delete;

  // Decompresses a chunk's records ("zstd" or "lz4") into exactly `uncompressed_size` bytes of
  // `out`. Throws FormatError for an unknown compression, a damaged stream, or a stream that holds
  // more or fewer bytes than declared; never writes beyond `uncompressed_size`.
  void decompress(const std::string& compression, const std::uint8_t* data, std::uint64_t size,
                  std::uint64_t uncompressed_size, Buffer& out);

 private:
  void decompressZstd(const std::uint8_t* data, std::uint64_t size, Buffer& out);
  void decompressLz4(const std::uint8_t* data, std::uint64_t size, Buffer& out);

  ZSTD_DCtx_s* zstd_ = nullptr;
  LZ4F_dctx_s* lz4_ = nullptr;
};

}  // namespace uampc::mcap::detail
