// The structure of a message type as its IDL file defines it: fields, their types and the constants
// of each struct. Parsed from the IDL (idl_parser.hpp), it is what the message definitions are
// written from (message_definition.hpp) and what the CDR decoder reads samples by (cdr_decoder.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace uampc {

// The primitive types of ROS 2 messages. A string is not one of them (its size varies).
enum class PrimitiveType {
  kBool,
  kByte,  // IDL octet
  kChar,
  kInt8,
  kUInt8,
  kInt16,
  kUInt16,
  kInt32,
  kUInt32,
  kInt64,
  kUInt64,
  kFloat32,  // IDL float
  kFloat64,  // IDL double
};

// How a .msg file names the type: "bool", "byte", "float64", ...
const char* msgPrimitiveName(PrimitiveType type);
// Bytes in CDR, which is also its alignment.
std::size_t cdrSize(PrimitiveType type);

// The type of one element of a field.
struct FieldType {
  enum class Kind { kPrimitive, kString, kStruct };
  Kind kind = Kind::kPrimitive;
  PrimitiveType primitive = PrimitiveType::kBool;  // kPrimitive
  std::uint32_t string_bound = 0;                  // kString: string<N>; 0: unbounded
  std::string struct_name;                         // kStruct: qualified, "geometry_msgs::msg::Pose"
};

struct FieldDefinition {
  enum class Collection { kSingle, kArray, kSequence };
  std::string name;
  FieldType type;
  Collection collection = Collection::kSingle;
  std::uint32_t size = 0;     // kArray: its length; kSequence: its bound, 0 when unbounded
  std::string default_value;  // @default, as a .msg writes it; empty when none
  std::string comment;        // the // comment after the field on its line, without the slashes
  int line = 0;               // in its IDL file
};

// "const uint8 INT8 = 1;" in the module <Struct>_Constants.
struct ConstantDefinition {
  std::string name;
  FieldType type;     // a primitive or a string
  std::string value;  // as a .msg writes it
};

struct StructDefinition {
  std::string name;  // qualified: "sensor_msgs::msg::PointCloud2"
  std::vector<ConstantDefinition> constants;
  std::vector<FieldDefinition> fields;
  std::string file;  // the IDL file it comes from ("sensor_msgs/msg/PointCloud2.idl")
  int line = 0;
};

// A message type and every struct its fields use, each by qualified name; every struct name a
// field refers to is in `structs`.
struct MessageStructure {
  std::string root;  // qualified name of the message's struct
  std::map<std::string, StructDefinition> structs;

  const StructDefinition& rootStruct() const { return structs.at(root); }
};

}  // namespace uampc
