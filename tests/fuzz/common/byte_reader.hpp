// Message fields from fuzz bytes, little-endian; past the end every read gives zeros, so that
// every input decodes to some message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uampc::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(u8()) << (8 * i);
    return v;
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  // A string of u8() bytes.
  std::string shortString() {
    const std::size_t n = u8();
    std::string s;
    for (std::size_t i = 0; i < n && pos_ < size_; ++i) s += static_cast<char>(data_[pos_++]);
    return s;
  }
  // Everything not read yet.
  std::vector<std::uint8_t> rest() {
    std::vector<std::uint8_t> out(data_ + (pos_ < size_ ? pos_ : size_), data_ + size_);
    pos_ = size_;
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace uampc::fuzz
