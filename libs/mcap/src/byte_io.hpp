// MCAP's primitive types (spec, "Serialization"): little-endian integers, strings and byte arrays
// with a uint32 length, maps and arrays with a uint32 byte length. Appending is unchecked;
// decoding goes through ByteCursor, which refuses to read past the end of the record.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace uampc::mcap::detail {

using Bytes = std::vector<std::uint8_t>;

// An allocator whose resize() leaves new bytes uninitialised.
template <typename T>
struct NoInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = NoInitAllocator<U>;
  };
  NoInitAllocator() = default;
  template <typename U>
  NoInitAllocator(const NoInitAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// A view of bytes someone else owns.
struct ByteView {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// Bytes read from the file or decompressed: they are written right after the buffer is sized,
// so zeroing it first (std::vector's resize) would cost as much again.
using Buffer = std::vector<std::uint8_t, NoInitAllocator<std::uint8_t>>;

// A record that does not decode. The reader adds the file name and the record's byte offset.
class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <typename T>
void putLittleEndian(Bytes& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

inline void putU8(Bytes& out, std::uint8_t v) { out.push_back(v); }
inline void putU16(Bytes& out, std::uint16_t v) { putLittleEndian(out, v); }
inline void putU32(Bytes& out, std::uint32_t v) { putLittleEndian(out, v); }
inline void putU64(Bytes& out, std::uint64_t v) { putLittleEndian(out, v); }
inline void putBytes(Bytes& out, const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  out.insert(out.end(), p, p + size);
}
void putString(Bytes& out, const std::string& s);  // uint32 length, then the bytes

// Writes a uint32 placeholder for the byte length of what follows (a map or array) and fills it
// in when the object goes out of scope.
class LengthPrefix {
 public:
  explicit LengthPrefix(Bytes& out);
  ~LengthPrefix();
  LengthPrefix(const LengthPrefix&) = delete;
  LengthPrefix& operator=(const LengthPrefix&) = delete;

 private:
  Bytes& out_;
  std::size_t at_;
};

template <typename T>
T getLittleEndian(const std::uint8_t* p) {
  T value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) value |= static_cast<T>(static_cast<T>(p[i]) << (8 * i));
  return value;
}

// Reads the fields of one record's content in order; every read is bounds-checked and names the
// field it was reading when the content ends early.
class ByteCursor {
 public:
  ByteCursor(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  std::uint8_t u8(const char* field);
  std::uint16_t u16(const char* field);
  std::uint32_t u32(const char* field);
  std::uint64_t u64(const char* field);
  std::string string(const char* field);
  // A view of the next `size` bytes (valid as long as the underlying buffer).
  const std::uint8_t* bytes(std::uint64_t size, const char* field);
  // A cursor over a uint32-length-prefixed map or array, which this cursor then skips.
  ByteCursor prefixed(const char* field);

  std::size_t remaining() const { return size_ - position_; }
  bool atEnd() const { return position_ == size_; }

 private:
  const std::uint8_t* take(std::uint64_t size, const char* field);

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

}  // namespace uampc::mcap::detail
