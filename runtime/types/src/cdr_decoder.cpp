#include "uampc/runtime/cdr_decoder.hpp"

#include <cstring>

namespace uampc {
namespace {

// A payload travels padded to a multiple of 4 bytes (Fast DDS pads a 21-byte sample to 24).
constexpr std::size_t kMostTrailingPadding = 3;

std::string hex(unsigned value) {
  const char digits[] = "0123456789abcdef";
  std::string text = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) text += digits[(value >> shift) & 0xf];
  return text;
}

// Whether the body is little endian, from the encapsulation header's representation identifier.
bool littleEndianBody(const std::uint8_t* data, std::size_t size) {
  if (size < kCdrEncapsulationSize) {
    throw CdrDecodeError("truncated sample: " + std::to_string(size) + " bytes, less than the 4-byte CDR header");
  }
  const unsigned representation = (unsigned{data[0]} << 8) | data[1];
  switch (representation) {
    case 0x0000:  // CDR_BE
      return false;
    case 0x0001:  // CDR_LE
      return true;
    case 0x0002:
    case 0x0003:
      throw CdrDecodeError("parameter-list CDR (PL_CDR, " + hex(representation) +
                           ") is not supported: ROS 2 types are plain CDR");
    case 0x0006:
    case 0x0007:
    case 0x0008:
    case 0x0009:
    case 0x000a:
    case 0x000b:
      throw CdrDecodeError("XCDR2 encapsulation " + hex(representation) +
                           " is not supported: only plain CDR (XCDR1, as Fast DDS 2.9 writes)");
    default:
      throw CdrDecodeError("unknown CDR encapsulation " + hex(representation));
  }
}

// Reads the body of a sample, keeping CDR's alignment and the names of the fields being read for
// the errors.
class CdrReader {
 public:
  CdrReader(const MessageStructure& structure, const std::uint8_t* data, std::size_t size)
      : structure_(structure),
        little_endian_(littleEndianBody(data, size)),
        body_(data + kCdrEncapsulationSize),
        size_(size - kCdrEncapsulationSize) {}

  DecodedValue sample() {
    DecodedValue value = structValue(structure_.rootStruct(), "");
    if (size_ - pos_ > kMostTrailingPadding) {
      throw CdrDecodeError(std::to_string(size_ - pos_) + " bytes left after the last field (offset " +
                           std::to_string(offset()) + " of " + std::to_string(size_ + kCdrEncapsulationSize) +
                           "): the sample is not a " + structure_.root);
    }
    return value;
  }

 private:
  std::size_t offset() const { return pos_ + kCdrEncapsulationSize; }  // in the whole sample, for errors

  void need(std::size_t bytes, const std::string& path) const {
    if (bytes <= size_ - pos_) return;
    throw CdrDecodeError("truncated sample: " + path + " needs " + std::to_string(bytes) + " bytes at offset " +
                         std::to_string(offset()) + ", " + std::to_string(size_ - pos_) + " left");
  }

  // Alignment is relative to the body; padding past the end counts as missing bytes.
  void align(std::size_t size, const std::string& path) {
    const std::size_t padding = (size - pos_ % size) % size;
    need(padding, path);
    pos_ += padding;
  }

  // An unsigned integer of `size` bytes in the sample's byte order, on any host.
  std::uint64_t unsignedBits(std::size_t size, const std::string& path) {
    align(size, path);
    need(size, path);
    std::uint64_t bits = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint64_t byte = body_[pos_ + i];
      bits |= byte << (8 * (little_endian_ ? i : size - 1 - i));
    }
    pos_ += size;
    return bits;
  }

  Scalar primitive(PrimitiveType type, const std::string& path) {
    const std::size_t size = cdrSize(type);
    const std::uint64_t bits = unsignedBits(size, path);
    Scalar s;
    s.type = type;
    switch (type) {
      case PrimitiveType::kBool:
        if (bits > 1) throw CdrDecodeError(path + ": a bool is " + std::to_string(bits) + ", neither 0 nor 1");
        s.boolean = bits == 1;
        break;
      case PrimitiveType::kInt8:
      case PrimitiveType::kInt16:
      case PrimitiveType::kInt32:
      case PrimitiveType::kInt64: {
        const unsigned unused = 64 - 8 * static_cast<unsigned>(size);  // sign-extend from the top bit
        s.signed_value = static_cast<std::int64_t>(bits << unused) >> unused;
        break;
      }
      case PrimitiveType::kFloat32: {
        const auto narrow = static_cast<std::uint32_t>(bits);
        float value;
        std::memcpy(&value, &narrow, sizeof value);
        s.real = value;
        break;
      }
      case PrimitiveType::kFloat64:
        std::memcpy(&s.real, &bits, sizeof s.real);
        break;
      default:
        s.unsigned_value = bits;
    }
    return s;
  }

  std::uint32_t length(const std::string& path) {
    return static_cast<std::uint32_t>(unsignedBits(4, path + " (length)"));
  }

  std::string text(std::uint32_t bound, const std::string& path) {
    const std::uint32_t size = length(path);
    need(size, path);
    const char* begin = reinterpret_cast<const char*>(body_ + pos_);
    pos_ += size;
    // The length counts the terminating NUL; an empty string may also be written as length 0.
    std::string value(begin, size > 0 && begin[size - 1] == '\0' ? size - 1 : size);
    if (bound && value.size() > bound) {
      throw CdrDecodeError(path + ": a string of " + std::to_string(value.size()) +
                           " characters, more than its bound " + std::to_string(bound));
    }
    return value;
  }

  DecodedValue element(const FieldType& type, const std::string& path) {
    DecodedValue value;
    switch (type.kind) {
      case FieldType::Kind::kPrimitive:
        value.kind = DecodedValue::Kind::kScalar;
        value.scalar = primitive(type.primitive, path);
        break;
      case FieldType::Kind::kString:
        value.kind = DecodedValue::Kind::kString;
        value.text = text(type.string_bound, path);
        break;
      case FieldType::Kind::kStruct:
        value = structValue(structure_.structs.at(type.struct_name), path);
        break;
    }
    return value;
  }

  DecodedValue structValue(const StructDefinition& s, const std::string& path) {
    DecodedValue value;
    value.kind = DecodedValue::Kind::kStruct;
    for (const FieldDefinition& field : s.fields) {
      const std::string field_path = path.empty() ? field.name : path + "." + field.name;
      value.fields.push_back({field.name, fieldValue(field, field_path)});
    }
    return value;
  }

  DecodedValue fieldValue(const FieldDefinition& field, const std::string& path) {
    switch (field.collection) {
      case FieldDefinition::Collection::kSingle:
        return element(field.type, path);
      case FieldDefinition::Collection::kArray:
        return elements(field.type, field.size, path);
      case FieldDefinition::Collection::kSequence:
        break;
    }
    const std::uint32_t count = length(path);
    if (field.size && count > field.size) {
      throw CdrDecodeError(path + ": a sequence of " + std::to_string(count) + " elements, more than its bound " +
                           std::to_string(field.size));
    }
    // A corrupt length must not allocate: every element takes at least minimumSize bytes.
    const std::size_t smallest = minimumSize(field.type);
    if (count > (size_ - pos_) / smallest) {
      throw CdrDecodeError("truncated sample: " + path + " has " + std::to_string(count) + " elements, more than the " +
                           std::to_string(size_ - pos_) + " bytes left can hold");
    }
    return elements(field.type, count, path);
  }

  DecodedValue elements(const FieldType& type, std::uint32_t count, const std::string& path) {
    DecodedValue value;
    if (type.kind == FieldType::Kind::kPrimitive) {
      value.kind = DecodedValue::Kind::kScalars;
      value.element_type = type.primitive;
      need(std::size_t{count} * cdrSize(type.primitive), path);
      value.scalars.reserve(count);
      for (std::uint32_t i = 0; i < count; ++i) value.scalars.push_back(primitive(type.primitive, path));
      return value;
    }
    value.kind = DecodedValue::Kind::kList;
    value.elements.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      value.elements.push_back(element(type, path + "[" + std::to_string(i) + "]"));
    }
    return value;
  }

  // The fewest bytes an element of the type can take (alignment not counted): at least 1.
  std::size_t minimumSize(const FieldType& type) const {
    switch (type.kind) {
      case FieldType::Kind::kPrimitive:
        return cdrSize(type.primitive);
      case FieldType::Kind::kString:
        return 4;
      case FieldType::Kind::kStruct:
        break;
    }
    std::size_t total = 0;
    for (const FieldDefinition& field : structure_.structs.at(type.struct_name).fields) {
      const std::size_t one = minimumSize(field.type);
      total += field.collection == FieldDefinition::Collection::kSequence ? 4
               : field.collection == FieldDefinition::Collection::kArray  ? one * field.size
                                                                          : one;
    }
    return total;
  }

  const MessageStructure& structure_;
  const bool little_endian_;
  const std::uint8_t* const body_;
  const std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace

const DecodedValue& DecodedValue::operator[](const std::string& field) const {
  for (const DecodedField& f : fields) {
    if (f.name == field) return f.value;
  }
  throw std::out_of_range("no field '" + field + "'");
}

DecodedValue decodeCdr(const MessageStructure& structure, const std::uint8_t* data, std::size_t size) {
  return CdrReader(structure, data, size).sample();
}

}  // namespace uampc
