#include "byte_io.hpp"

#include <limits>

namespace uampc::mcap::detail {

void putString(Bytes& out, const std::string& s) {
  if (s.size() > std::numeric_limits<std::uint32_t>::max()) throw FormatError("a string longer than 4 GiB");
  putU32(out, static_cast<std::uint32_t>(s.size()));
  putBytes(out, s.data(), s.size());
}

LengthPrefix::LengthPrefix(Bytes& out) : out_(out), at_(out.size()) { putU32(out_, 0); }

LengthPrefix::~LengthPrefix() {
  const auto length = static_cast<std::uint32_t>(out_.size() - at_ - 4);
  for (std::size_t i = 0; i < 4; ++i) out_[at_ + i] = static_cast<std::uint8_t>(length >> (8 * i));
}

const std::uint8_t* ByteCursor::take(std::uint64_t size, const char* field) {
  if (size > remaining()) {
    throw FormatError(std::string("field ") + field + " needs " + std::to_string(size) + " bytes but the record has " +
                      std::to_string(remaining()) + " left");
  }
  const std::uint8_t* p = data_ + position_;
  position_ += static_cast<std::size_t>(size);
  return p;
}

std::uint8_t ByteCursor::u8(const char* field) { return *take(1, field); }
std::uint16_t ByteCursor::u16(const char* field) { return getLittleEndian<std::uint16_t>(take(2, field)); }
std::uint32_t ByteCursor::u32(const char* field) { return getLittleEndian<std::uint32_t>(take(4, field)); }
std::uint64_t ByteCursor::u64(const char* field) { return getLittleEndian<std::uint64_t>(take(8, field)); }

std::string ByteCursor::string(const char* field) {
  const std::uint32_t size = u32(field);
  const auto* p = take(size, field);
  return std::string(reinterpret_cast<const char*>(p), size);
}

const std::uint8_t* ByteCursor::bytes(std::uint64_t size, const char* field) { return take(size, field); }

ByteCursor ByteCursor::prefixed(const char* field) {
  const std::uint32_t size = u32(field);
  return ByteCursor(take(size, field), size);
}

}  // namespace uampc::mcap::detail
