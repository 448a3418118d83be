// The CRC-32 the MCAP spec names for chunk, summary and data section checksums: ISO-HDLC / zlib
// (reflected polynomial 0xEDB88320, initial value and final XOR 0xFFFFFFFF), computed by zlib.
#pragma once

#include <zlib.h>

#include <cstddef>
#include <cstdint>

namespace uampc::mcap::detail {

class Crc32 {
 public:
  void update(const void* data, std::size_t size) {
    state_ = crc32_z(state_, static_cast<const Bytef*>(data), static_cast<z_size_t>(size));
  }
  std::uint32_t value() const { return static_cast<std::uint32_t>(state_); }

 private:
  uLong state_ = crc32_z(0L, Z_NULL, 0);
};

inline std::uint32_t crc32(const void* data, std::size_t size) {
  Crc32 crc;
  crc.update(data, size);
  return crc.value();
}

}  // namespace uampc::mcap::detail
