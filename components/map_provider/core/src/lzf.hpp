// LZF, the compression of binary_compressed PCD files (docs/decisions/pcd-own-reader.md).
//
// An LZF stream is a sequence of items, each starting with a control byte c:
//   c < 32:  a literal run: the next c + 1 bytes are copied to the output;
//   c >= 32: a back reference: length L = c >> 5 (if 7, plus the next byte), then distance
//            D = ((c & 31) << 8) + the next byte; L + 2 bytes are copied from D + 1 bytes back
//            in the output (they may overlap what is being written).
// So a reference copies 3 to 264 bytes from at most 8192 bytes back.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace uampc::world {

// What is wrong with compressed data; the PCD reader adds the file's name.
class LzfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Decompresses `in` into exactly `out_size` bytes at `out`. Never writes past out + out_size and
// never reads past the end of `in`: data that would, that refers to bytes before the start of the
// output, or that expands to another size than out_size throws LzfError.
void lzfDecompress(std::string_view in, char* out, std::size_t out_size);

// LZF of `in` (greedy matching; at most in.size() / 32 + 1 bytes larger than `in`).
std::string lzfCompress(std::string_view in);

}  // namespace uampc::world
