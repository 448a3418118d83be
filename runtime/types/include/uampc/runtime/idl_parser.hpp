// A parser of the IDL that ROS 2 message packages are written in: the subset uampc's idl/ and
// rosidl's generated .idl files use. Read: #include, modules, structs, `const` in <Struct>_Constants
// modules, typedefs of arrays, sequence<T>, sequence<T, N>, T name[N], string, string<N>, the
// primitive types, other structs by (scoped) name, @default annotations (other annotations are
// skipped) and comments. Anything else (unions, enums, wide strings, nested sequences, ...) is an
// error naming file and line.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/runtime/message_structure.hpp"

namespace uampc {

// "file:line: what is wrong".
class IdlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct IdlFile {
  std::vector<std::string> includes;  // as #include names them: "std_msgs/msg/Header.idl"
  // In file order. A field's struct_name is as the IDL writes it ("Point", "geometry_msgs::msg::Point");
  // loadMessageStructure (message_definition.hpp) resolves it to a qualified name.
  std::vector<StructDefinition> structs;
};

// Parses one IDL file; `file` names it in errors and in StructDefinition::file.
IdlFile parseIdl(const std::string& text, const std::string& file);

}  // namespace uampc
