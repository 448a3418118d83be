// IDL as the runtime reads a message package's files (user IDL, embedded by
// uampc_add_message_library and parsed when the type is first asked for): parseIdl() on the input
// as fuzz_msgs/msg/Sample.idl, then loadMessageStructure() of fuzz_msgs/msg/Sample with the
// shipped IDL files for its #includes, and the ros2msg text a recording writes for it. Bad IDL
// must end in IdlError naming file and line.
#include <cstddef>
#include <cstdint>
#include <string>

#include "uampc/runtime/idl_parser.hpp"
#include "uampc/runtime/message_definition.hpp"
#include "uampc/runtime/message_type.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace uampc;
  static const std::string path = "fuzz_msgs/msg/Sample.idl";
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    parseIdl(text, path);
    const auto structure = loadMessageStructure("fuzz_msgs/msg/Sample", [&](const std::string& file) {
      return file == path ? text.c_str() : findIdlFile(file);
    });
    if (structure) ros2msgDefinition(*structure);
  } catch (const IdlError&) {
  }
  return 0;
}
