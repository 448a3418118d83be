#include "compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <new>

namespace uampc::mcap::detail {

namespace {

// zstd at level -1 with long-distance matching, chosen by measurement
// (docs/results/recording-cost.md). The recorder runs beside the system it records and may cost it
// at most 10 % of its real-time factor. Half of a default run's bytes are /lo/local_map, a 540 kB
// cloud that changes little from one sample to the next: level 1's 512 kB window cannot reach the
// previous sample, so it compresses a 4 MiB chunk only 1.41x at 0.53 GB/s, whereas long-distance
// matching finds the repeats across the whole chunk (2.32x at 0.98 GB/s on one core of this
// machine). The window follows the chunk: zstd shrinks it to the size of the input it is given.
constexpr int kZstdLevel = -1;

void checkLz4(std::size_t result, const char* what) {
  if (LZ4F_isError(result)) throw FormatError(std::string(what) + LZ4F_getErrorName(result));
}

std::string sizeMismatch(const char* compression, std::uint64_t decoded, std::uint64_t declared) {
  return std::string(compression) + " data decompresses to " + std::to_string(decoded) + " bytes, the chunk declares " +
         std::to_string(declared);
}

}  // namespace

std::string compressionName(Compression compression) {
  switch (compression) {
    case Compression::kZstd:
      return "zstd";
    case Compression::kLz4:
      return "lz4";
    case Compression::kNone:
      break;
  }
  return "";
}

ChunkCompressor::ChunkCompressor(Compression compression) : compression_(compression) {
  if (compression_ == Compression::kZstd) {
    if (!(zstd_ = ZSTD_createCCtx())) throw std::bad_alloc();
    if (ZSTD_isError(ZSTD_CCtx_setParameter(zstd_, ZSTD_c_compressionLevel, kZstdLevel)) ||
        ZSTD_isError(ZSTD_CCtx_setParameter(zstd_, ZSTD_c_enableLongDistanceMatching, 1))) {
      ZSTD_freeCCtx(zstd_);
      throw FormatError("this libzstd does not take the recorder's zstd parameters");
    }
  }
  if (compression_ == Compression::kLz4 && LZ4F_isError(LZ4F_createCompressionContext(&lz4_, LZ4F_VERSION)))
    throw std::bad_alloc();
}

ChunkCompressor::~ChunkCompressor() {
  ZSTD_freeCCtx(zstd_);
  LZ4F_freeCompressionContext(lz4_);
}

ByteView ChunkCompressor::compress(const Bytes& in) {
  switch (compression_) {
    case Compression::kZstd: {
      out_.resize(ZSTD_compressBound(in.size()));
      const std::size_t n = ZSTD_compress2(zstd_, out_.data(), out_.size(), in.data(), in.size());
      if (ZSTD_isError(n)) throw FormatError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
      return {out_.data(), n};
    }
    case Compression::kLz4:
      return compressLz4(in);
    case Compression::kNone:
      break;
  }
  return {in.data(), in.size()};
}

// One LZ4 frame: header, blocks, end mark.
ByteView ChunkCompressor::compressLz4(const Bytes& in) {
  LZ4F_preferences_t preferences{};
  preferences.frameInfo.contentSize = in.size();  // lets a reader check the size before decoding
  preferences.frameInfo.blockSizeID = LZ4F_max4MB;
  out_.resize(LZ4F_HEADER_SIZE_MAX + LZ4F_compressBound(in.size(), &preferences));
  std::size_t at = LZ4F_compressBegin(lz4_, out_.data(), out_.size(), &preferences);
  checkLz4(at, "lz4 compression failed: ");
  const std::size_t body = LZ4F_compressUpdate(lz4_, out_.data() + at, out_.size() - at, in.data(), in.size(), nullptr);
  checkLz4(body, "lz4 compression failed: ");
  at += body;
  const std::size_t end = LZ4F_compressEnd(lz4_, out_.data() + at, out_.size() - at, nullptr);
  checkLz4(end, "lz4 compression failed: ");
  return {out_.data(), at + end};
}

ChunkDecompressor::ChunkDecompressor() {
  if (!(zstd_ = ZSTD_createDCtx())) throw std::bad_alloc();
  if (LZ4F_isError(LZ4F_createDecompressionContext(&lz4_, LZ4F_VERSION))) {
    ZSTD_freeDCtx(zstd_);
    throw std::bad_alloc();
  }
}

ChunkDecompressor::~ChunkDecompressor() {
  ZSTD_freeDCtx(zstd_);
  LZ4F_freeDecompressionContext(lz4_);
}

void ChunkDecompressor::decompress(const std::string& compression, const std::uint8_t* data, std::uint64_t size,
                                   std::uint64_t uncompressed_size, Buffer& out) {
  out.resize(uncompressed_size);
  if (compression == "zstd") return decompressZstd(data, size, out);
  if (compression == "lz4") return decompressLz4(data, size, out);
  throw FormatError("unsupported chunk compression '" + compression + "' (uampc reads zstd, lz4 and none)");
}

void ChunkDecompressor::decompressZstd(const std::uint8_t* data, std::uint64_t size, Buffer& out) {
  const std::size_t n = ZSTD_decompressDCtx(zstd_, out.data(), out.size(), data, size);
  if (ZSTD_isError(n)) throw FormatError(std::string("zstd data does not decompress: ") + ZSTD_getErrorName(n));
  if (n != out.size()) throw FormatError(sizeMismatch("zstd", n, out.size()));
}

void ChunkDecompressor::decompressLz4(const std::uint8_t* data, std::uint64_t size, Buffer& out) {
  LZ4F_resetDecompressionContext(lz4_);  // the last chunk may have stopped in the middle of a frame
  std::uint64_t in_at = 0, out_at = 0;
  std::size_t hint = 1;  // LZ4F_decompress returns 0 when a frame is complete
  while (in_at < size) {
    std::size_t out_size = static_cast<std::size_t>(out.size() - out_at);
    std::size_t in_size = static_cast<std::size_t>(size - in_at);
    hint = LZ4F_decompress(lz4_, out.data() + out_at, &out_size, data + in_at, &in_size, nullptr);
    checkLz4(hint, "lz4 data does not decompress: ");
    if (in_size == 0 && out_size == 0) {
      throw FormatError("lz4 data decompresses to more than the " + std::to_string(out.size()) +
                        " bytes the chunk declares");
    }
    in_at += in_size;
    out_at += out_size;
  }
  if (hint != 0) throw FormatError("lz4 frame is cut off");
  if (out_at != out.size()) throw FormatError(sizeMismatch("lz4", out_at, out.size()));
}

}  // namespace uampc::mcap::detail
