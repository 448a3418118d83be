// Decodes a sample of any message type whose structure is known (message_definition.hpp) from its
// CDR bytes into a tree of values, for tools that look at samples they were not compiled for
// (`uampc topic echo`). The bytes are the DDS payload: the 4-byte encapsulation header, then plain
// CDR (XCDR1) in either byte order, with the alignment Fast DDS 2.9 (Fast CDR 1.0) and every ROS 2
// rmw use: a primitive of n bytes starts at a multiple of n counted from the end of the header; a
// string and a sequence are a uint32 length (a string's counts its terminating NUL) then their
// elements; an array is its elements only; a struct is its fields, with no padding of its own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/runtime/message_structure.hpp"

namespace uampc {

// A CDR sample starts with its encapsulation header: representation id (2 bytes) and options (2 bytes).
inline constexpr std::size_t kCdrEncapsulationSize = 4;

// What is wrong with the bytes: "truncated sample: header.frame_id needs 10 bytes at offset 16, 4 left".
class CdrDecodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A number or boolean with its type.
struct Scalar {
  PrimitiveType type = PrimitiveType::kBool;
  union {
    bool boolean;                  // kBool
    std::int64_t signed_value;     // kInt8 .. kInt64
    std::uint64_t unsigned_value;  // kByte, kChar, kUInt8 .. kUInt64
    double real;                   // kFloat32 (exactly widened), kFloat64
  };
  Scalar() : unsigned_value(0) {}
};

struct DecodedField;

// One value of a decoded sample: a scalar, a string, a struct, or an array or sequence.
struct DecodedValue {
  enum class Kind { kScalar, kString, kStruct, kScalars, kList };
  Kind kind = Kind::kScalar;
  Scalar scalar;                       // kScalar
  std::string text;                    // kString
  std::vector<DecodedField> fields;    // kStruct, in the order the IDL declares them
  PrimitiveType element_type{};        // kScalars
  std::vector<Scalar> scalars;         // kScalars: the elements of an array or sequence of a primitive type
  std::vector<DecodedValue> elements;  // kList: the elements of an array or sequence of strings or structs

  // A struct's field; throws std::out_of_range naming it when there is none.
  const DecodedValue& operator[](const std::string& field) const;
};

struct DecodedField {
  std::string name;
  DecodedValue value;
};

// Decodes one sample of the structure's root type. Throws CdrDecodeError when the bytes are not
// such a sample: too short, an encapsulation other than plain CDR, a length longer than what is
// left (checked before anything is allocated), a bool that is neither 0 nor 1, a string longer than
// its bound or more than 3 bytes (alignment padding) left over at the end.
DecodedValue decodeCdr(const MessageStructure& structure, const std::uint8_t* data, std::size_t size);

}  // namespace uampc
