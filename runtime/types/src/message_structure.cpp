#include "uampc/runtime/message_structure.hpp"

namespace uampc {

const char* msgPrimitiveName(PrimitiveType type) {
  switch (type) {
    case PrimitiveType::kBool:
      return "bool";
    case PrimitiveType::kByte:
      return "byte";
    case PrimitiveType::kChar:
      return "char";
    case PrimitiveType::kInt8:
      return "int8";
    case PrimitiveType::kUInt8:
      return "uint8";
    case PrimitiveType::kInt16:
      return "int16";
    case PrimitiveType::kUInt16:
      return "uint16";
    case PrimitiveType::kInt32:
      return "int32";
    case PrimitiveType::kUInt32:
      return "uint32";
    case PrimitiveType::kInt64:
      return "int64";
    case PrimitiveType::kUInt64:
      return "uint64";
    case PrimitiveType::kFloat32:
      return "float32";
    case PrimitiveType::kFloat64:
      return "float64";
  }
  return "?";
}

std::size_t cdrSize(PrimitiveType type) {
  switch (type) {
    case PrimitiveType::kBool:
    case PrimitiveType::kByte:
    case PrimitiveType::kChar:
    case PrimitiveType::kInt8:
    case PrimitiveType::kUInt8:
      return 1;
    case PrimitiveType::kInt16:
    case PrimitiveType::kUInt16:
      return 2;
    case PrimitiveType::kInt32:
    case PrimitiveType::kUInt32:
    case PrimitiveType::kFloat32:
      return 4;
    case PrimitiveType::kInt64:
    case PrimitiveType::kUInt64:
    case PrimitiveType::kFloat64:
      return 8;
  }
  return 1;
}

}  // namespace uampc
