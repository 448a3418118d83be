#include "compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>

namespace uampc::mcap::detail {

namespace {

// zstd level 1: the recorder runs beside the system it records, whose real-time factor it may cost
// at most 10 %; higher levels buy a few percent of size on point clouds for several times the CPU.
constexpr int kZstdLevel = 1;

void compressLz4(const Bytes& in, Bytes& out) {
  LZ4F_preferences_t preferences{};
  preferences.frameInfo.contentSize = in.size();  // lets a reader check the size before decoding
  preferences.frameInfo.blockSizeID = LZ4F_max4MB;
  out.resize(LZ4F_compressFrameBound(in.size(), &preferences));
  const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &preferences);
  if (LZ4F_isError(n)) throw FormatError(std::string("lz4 compression failed: ") + LZ4F_getErrorName(n));
  out.resize(n);
}

Bytes decompressZstd(const std::uint8_t* data, std::uint64_t size, std::uint64_t uncompressed_size) {
  Bytes out(uncompressed_size);
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), ZSTD_freeDCtx);
  const std::size_t n = ZSTD_decompressDCtx(context.get(), out.data(), out.size(), data, size);
  if (ZSTD_isError(n)) throw FormatError(std::string("zstd data does not decompress: ") + ZSTD_getErrorName(n));
  if (n != uncompressed_size) {
    throw FormatError("zstd data decompresses to " + std::to_string(n) + " bytes, the chunk declares " +
                      std::to_string(uncompressed_size));
  }
  return out;
}

Bytes decompressLz4(const std::uint8_t* data, std::uint64_t size, std::uint64_t uncompressed_size) {
  Bytes out(uncompressed_size);
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw FormatError("lz4: out of memory");
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(raw, LZ4F_freeDecompressionContext);
  std::uint64_t in_at = 0, out_at = 0;
  std::size_t hint = 1;  // LZ4F_decompress returns 0 when a frame is complete
  while (in_at < size) {
    std::size_t out_size = static_cast<std::size_t>(uncompressed_size - out_at);
    std::size_t in_size = static_cast<std::size_t>(size - in_at);
    hint = LZ4F_decompress(context.get(), out.data() + out_at, &out_size, data + in_at, &in_size, nullptr);
    if (LZ4F_isError(hint)) throw FormatError(std::string("lz4 data does not decompress: ") + LZ4F_getErrorName(hint));
    if (in_size == 0 && out_size == 0) {
      throw FormatError("lz4 data decompresses to more than the " + std::to_string(uncompressed_size) +
                        " bytes the chunk declares");
    }
    in_at += in_size;
    out_at += out_size;
  }
  if (hint != 0) throw FormatError("lz4 frame is cut off");
  if (out_at != uncompressed_size) {
    throw FormatError("lz4 data decompresses to " + std::to_string(out_at) + " bytes, the chunk declares " +
                      std::to_string(uncompressed_size));
  }
  return out;
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
  if (compression_ == Compression::kZstd) zstd_ = ZSTD_createCCtx();
}

ChunkCompressor::~ChunkCompressor() { ZSTD_freeCCtx(zstd_); }

const Bytes& ChunkCompressor::compress(const Bytes& in) {
  switch (compression_) {
    case Compression::kZstd: {
      out_.resize(ZSTD_compressBound(in.size()));
      const std::size_t n = ZSTD_compressCCtx(zstd_, out_.data(), out_.size(), in.data(), in.size(), kZstdLevel);
      if (ZSTD_isError(n)) throw FormatError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
      out_.resize(n);
      return out_;
    }
    case Compression::kLz4:
      compressLz4(in, out_);
      return out_;
    case Compression::kNone:
      break;
  }
  return in;
}

Bytes decompress(const std::string& compression, const std::uint8_t* data, std::uint64_t size,
                 std::uint64_t uncompressed_size) {
  if (compression == "zstd") return decompressZstd(data, size, uncompressed_size);
  if (compression == "lz4") return decompressLz4(data, size, uncompressed_size);
  if (compression.empty()) {
    if (size != uncompressed_size) {
      throw FormatError("uncompressed chunk holds " + std::to_string(size) + " bytes but declares " +
                        std::to_string(uncompressed_size));
    }
    return Bytes(data, data + size);
  }
  throw FormatError("unsupported chunk compression '" + compression + "' (uampc reads zstd, lz4 and none)");
}

}  // namespace uampc::mcap::detail
