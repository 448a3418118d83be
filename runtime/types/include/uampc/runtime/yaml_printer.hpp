// A decoded sample (cdr_decoder.hpp) as YAML, laid out like `ros2 topic echo`: one "field: value"
// per line, nested structs indented by two spaces, sequences of structs as "- " items, sequences of
// numbers, booleans or strings in flow style ("[1.0, 2.5]"). Floats are printed with the fewest
// digits that read back to the same float32 or float64 ("0.1", never "0.100000001"), so a value can
// be copied from the output exactly, always with a '.' as PyYAML writes them ("1.0", "1.0e-05"). Long byte arrays
// (byte, uint8, char) are elided to "<N bytes>" unless `full` is set. Strings are quoted where YAML needs it.
#pragma once

#include <cstddef>
#include <string>

#include "uampc/runtime/cdr_decoder.hpp"

namespace uampc {

struct YamlOptions {
  bool full = false;  // print byte arrays of any length
};

// Byte arrays longer than this are elided unless YamlOptions::full.
constexpr std::size_t kLongestBytesShown = 32;

// The fields of a decoded struct, one per line, each line ending in '\n'.
std::string toYaml(const DecodedValue& message, const YamlOptions& options = {});

// One scalar as YAML writes it: "true", "-3", "0.1", ".nan".
std::string yamlScalar(const Scalar& value);
// A string as a YAML scalar: plain when that reads back as the same string, quoted otherwise.
std::string yamlString(const std::string& text);

}  // namespace uampc
