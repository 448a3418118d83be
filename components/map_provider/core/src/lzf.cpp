// LZF for binary_compressed PCD files; the format is described in lzf.hpp.
#include "lzf.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace uampc::world {
namespace {

constexpr std::size_t kMaxLiteralRun = 32;
constexpr std::size_t kMinMatch = 3;
constexpr std::size_t kMaxMatch = 264;       // 2 + 7 + 255
constexpr std::size_t kMaxDistance = 8192;  // 13 bits, counted from 1
constexpr unsigned kHashBits = 14;

unsigned byteAt(std::string_view in, std::size_t i) { return static_cast<unsigned char>(in[i]); }

// The next byte of `in` at `pos`, or LzfError naming what it was needed for.
unsigned nextByte(std::string_view in, std::size_t& pos, const char* what) {
  if (pos >= in.size()) throw LzfError(std::string("compressed data ends inside ") + what);
  return byteAt(in, pos++);
}

void checkRoom(std::size_t written, std::size_t more, std::size_t out_size) {
  if (more > out_size - written) {
    throw LzfError("compressed data expands beyond its declared " + std::to_string(out_size) + " bytes");
  }
}

// Copies `length` bytes from `distance` bytes back; byte by byte where they overlap, since a
// reference may repeat what it is writing (distance 1 repeats one byte).
void copyBack(char* out, std::size_t at, std::size_t distance, std::size_t length) {
  if (distance >= length) {
    std::memcpy(out + at, out + at - distance, length);
    return;
  }
  for (std::size_t k = 0; k < length; ++k) out[at + k] = out[at - distance + k];
}

// Appends in[begin, end) as literal runs of at most 32 bytes.
void putLiterals(std::string& out, std::string_view in, std::size_t begin, std::size_t end) {
  while (begin < end) {
    const std::size_t n = std::min(end - begin, kMaxLiteralRun);
    out.push_back(static_cast<char>(n - 1));
    out.append(in.data() + begin, n);
    begin += n;
  }
}

void putReference(std::string& out, std::size_t distance, std::size_t length) {
  const std::size_t d = distance - 1, l = length - 2;  // l >= 1: the control byte is >= 32
  if (l < 7) {
    out.push_back(static_cast<char>((l << 5) | (d >> 8)));
  } else {
    out.push_back(static_cast<char>((7u << 5) | (d >> 8)));
    out.push_back(static_cast<char>(l - 7));
  }
  out.push_back(static_cast<char>(d & 0xff));
}

std::size_t hashAt(std::string_view in, std::size_t i) {
  const std::uint32_t v = (byteAt(in, i) << 16) | (byteAt(in, i + 1) << 8) | byteAt(in, i + 2);
  return (v * 2654435761u) >> (32 - kHashBits);
}

std::size_t matchLength(std::string_view in, std::size_t from, std::size_t at) {
  const std::size_t limit = std::min(kMaxMatch, in.size() - at);
  std::size_t n = 0;
  while (n < limit && in[from + n] == in[at + n]) ++n;
  return n;
}

}  // namespace

void lzfDecompress(std::string_view in, char* out, std::size_t out_size) {
  std::size_t pos = 0, written = 0;
  while (pos < in.size()) {
    const unsigned control = byteAt(in, pos++);
    if (control < kMaxLiteralRun) {
      const std::size_t n = control + 1;
      if (n > in.size() - pos) throw LzfError("compressed data ends inside a literal run");
      checkRoom(written, n, out_size);
      std::memcpy(out + written, in.data() + pos, n);
      pos += n;
      written += n;
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) length += nextByte(in, pos, "a back reference's length");
    length += 2;
    const std::size_t distance = ((control & 31u) << 8) + nextByte(in, pos, "a back reference") + 1;
    if (distance > written) throw LzfError("a back reference points before the start of the data");
    checkRoom(written, length, out_size);
    copyBack(out, written, distance, length);
    written += length;
  }
  if (written != out_size) {
    throw LzfError("compressed data expands to " + std::to_string(written) + " bytes, not the declared " +
                   std::to_string(out_size));
  }
}

std::string lzfCompress(std::string_view in) {
  std::string out;
  out.reserve(in.size() + in.size() / kMaxLiteralRun + 1);
  constexpr std::size_t kNone = SIZE_MAX;
  std::vector<std::size_t> last_seen(std::size_t{1} << kHashBits, kNone);
  std::size_t literal_start = 0, at = 0;
  while (at + kMinMatch <= in.size()) {
    const std::size_t h = hashAt(in, at);
    const std::size_t candidate = last_seen[h];
    last_seen[h] = at;
    const std::size_t length =
        candidate != kNone && at - candidate <= kMaxDistance ? matchLength(in, candidate, at) : 0;
    if (length < kMinMatch) {
      ++at;
      continue;
    }
    putLiterals(out, in, literal_start, at);
    putReference(out, at - candidate, length);
    // The positions inside the match become candidates too (better matches later on).
    for (std::size_t k = at + 1; k < at + length && k + kMinMatch <= in.size(); ++k) last_seen[hashAt(in, k)] = k;
    at += length;
    literal_start = at;
  }
  putLiterals(out, in, literal_start, in.size());
  return out;
}

}  // namespace uampc::world
