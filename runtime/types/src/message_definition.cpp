#include "uampc/runtime/message_definition.hpp"

#include <set>

#include "uampc/runtime/idl_parser.hpp"
#include "uampc/runtime/message_type.hpp"

namespace uampc {
namespace {

const std::string kSeparator(80, '=');

// "a::b::C" -> "a::b"; "" for a name at global scope.
std::string scopeOf(const std::string& qualified) {
  const auto cut = qualified.rfind("::");
  return cut == std::string::npos ? "" : qualified.substr(0, cut);
}

std::string packageOf(const std::string& qualified) { return qualified.substr(0, qualified.find("::")); }

// Every struct of a file and of the files it includes (transitively), by qualified name.
class StructCollector {
 public:
  explicit StructCollector(const IdlFileSource& files) : files_(files) {}

  // False when the file does not exist.
  bool load(const std::string& path, const std::string& included_from) {
    if (!loaded_.insert(path).second) return true;
    const char* text = files_(path);
    if (!text) {
      if (included_from.empty()) return false;
      throw IdlError(included_from + ": #include \"" + path + "\": no loaded message library has this file");
    }
    IdlFile file = parseIdl(text, path);
    for (StructDefinition& s : file.structs) {
      const auto existing = structs_.find(s.name);
      if (existing != structs_.end()) {
        throw IdlError(path + ":" + std::to_string(s.line) + ": struct " + s.name + " is already defined in " +
                       existing->second.file + ":" + std::to_string(existing->second.line));
      }
      structs_.emplace(s.name, std::move(s));
    }
    for (const std::string& include : file.includes) load(include, path);
    return true;
  }

  // Makes every field's struct name qualified, looking in the field's scope, then outwards (IDL's
  // scoping: "Point" inside geometry_msgs::msg is geometry_msgs::msg::Point).
  void resolveNames() {
    for (auto& [name, s] : structs_) {
      for (FieldDefinition& field : s.fields) {
        if (field.type.kind == FieldType::Kind::kStruct) field.type.struct_name = resolve(field, s);
      }
    }
  }

  std::map<std::string, StructDefinition>& structs() { return structs_; }

 private:
  std::string resolve(const FieldDefinition& field, const StructDefinition& owner) const {
    const std::string& written = field.type.struct_name;
    for (std::string scope = scopeOf(owner.name);; scope = scopeOf(scope)) {
      const std::string candidate = scope.empty() ? written : scope + "::" + written;
      if (structs_.count(candidate)) return candidate;
      if (scope.empty()) break;
    }
    throw IdlError(owner.file + ":" + std::to_string(field.line) + ": unknown type '" + written +
                   "' (no struct of that name in this file or the files it includes)");
  }

  const IdlFileSource& files_;
  std::set<std::string> loaded_;
  std::map<std::string, StructDefinition> structs_;
};

// Copies `name` and every struct it uses into `out`; a struct met again while its own fields are
// being followed contains itself, which no message can.
void collectUsed(const std::string& name, std::map<std::string, StructDefinition>& all,
                 std::set<std::string>& in_progress, MessageStructure& out) {
  if (out.structs.count(name)) return;
  const StructDefinition& s = all.at(name);
  if (!in_progress.insert(name).second) {
    throw IdlError(s.file + ":" + std::to_string(s.line) + ": struct " + name + " contains itself");
  }
  for (const FieldDefinition& field : s.fields) {
    if (field.type.kind == FieldType::Kind::kStruct) collectUsed(field.type.struct_name, all, in_progress, out);
  }
  in_progress.erase(name);
  out.structs.emplace(name, s);
}

std::string typeText(const FieldType& type, FieldDefinition::Collection collection, std::uint32_t size,
                     const std::string& package) {
  std::string text;
  switch (type.kind) {
    case FieldType::Kind::kPrimitive:
      text = msgPrimitiveName(type.primitive);
      break;
    case FieldType::Kind::kString:
      text = type.string_bound ? "string<=" + std::to_string(type.string_bound) : "string";
      break;
    case FieldType::Kind::kStruct:
      text = packageOf(type.struct_name) == package ? type.struct_name.substr(type.struct_name.rfind("::") + 2)
                                                    : msgTypeName(type.struct_name);
      break;
  }
  switch (collection) {
    case FieldDefinition::Collection::kSingle:
      return text;
    case FieldDefinition::Collection::kArray:
      return text + "[" + std::to_string(size) + "]";
    case FieldDefinition::Collection::kSequence:
      return text + (size ? "[<=" + std::to_string(size) + "]" : "[]");
  }
  return text;
}

std::string msgText(const StructDefinition& s) {
  const std::string package = packageOf(s.name);
  std::string text;
  for (const ConstantDefinition& c : s.constants) {
    text += typeText(c.type, FieldDefinition::Collection::kSingle, 0, package) + " " + c.name + "=" + c.value + "\n";
  }
  for (const FieldDefinition& f : s.fields) {
    text += typeText(f.type, f.collection, f.size, package) + " " + f.name;
    if (!f.default_value.empty()) text += " " + f.default_value;
    if (!f.comment.empty()) text += "  # " + f.comment;
    text += "\n";
  }
  return text;
}

void appendWithDependencies(const MessageStructure& structure, const std::string& name, std::set<std::string>& written,
                            std::string& text) {
  const StructDefinition& s = structure.structs.at(name);
  text += msgText(s);
  std::map<std::string, std::string> dependencies;  // by .msg name, the order rosbag2 follows them in
  for (const FieldDefinition& f : s.fields) {
    if (f.type.kind == FieldType::Kind::kStruct)
      dependencies.emplace(msgTypeName(f.type.struct_name), f.type.struct_name);
  }
  for (const auto& [msg_name, qualified] : dependencies) {
    if (!written.insert(msg_name).second) continue;
    text += "\n" + kSeparator + "\nMSG: " + msg_name + "\n";
    appendWithDependencies(structure, qualified, written, text);
  }
}

}  // namespace

std::string msgTypeName(const std::string& qualified_struct_name) {
  std::string name;
  std::size_t start = 0;
  while (true) {
    const auto cut = qualified_struct_name.find("::", start);
    const std::string part = qualified_struct_name.substr(start, cut == std::string::npos ? cut : cut - start);
    // The "msg" module of ROS packages is left out: sensor_msgs/PointField.
    const bool msg_module = part == "msg" && start != 0 && cut != std::string::npos;
    if (!msg_module) name += (name.empty() ? "" : "/") + part;
    if (cut == std::string::npos) return name;
    start = cut + 2;
  }
}

std::optional<MessageStructure> loadMessageStructure(const std::string& ros_name, const IdlFileSource& files) {
  // "pkg/msg/Name": its file is pkg/msg/Name.idl, its struct pkg::msg::Name.
  const auto first = ros_name.find('/');
  const auto last = ros_name.rfind('/');
  if (first == std::string::npos || first == 0 || last == first || last + 1 == ros_name.size() ||
      ros_name.find('/', first + 1) != last) {
    return std::nullopt;
  }
  StructCollector collector(files);
  if (!collector.load(ros_name + ".idl", "")) return std::nullopt;
  collector.resolveNames();
  MessageStructure structure;
  structure.root = ros_name.substr(0, first) + "::" + ros_name.substr(first + 1, last - first - 1) +
                   "::" + ros_name.substr(last + 1);
  if (!collector.structs().count(structure.root)) {
    throw IdlError(ros_name + ".idl: defines no struct " + structure.root);
  }
  std::set<std::string> in_progress;
  collectUsed(structure.root, collector.structs(), in_progress, structure);
  return structure;
}

std::optional<MessageStructure> findMessageStructure(const std::string& ros_name) {
  return loadMessageStructure(ros_name, [](const std::string& path) { return findIdlFile(path); });
}

std::string ros2msgDefinition(const MessageStructure& structure) {
  std::string text;
  std::set<std::string> written = {msgTypeName(structure.root)};
  appendWithDependencies(structure, structure.root, written, text);
  return text;
}

std::string messageDefinition(const std::string& ros_name) {
  const std::optional<MessageStructure> structure = findMessageStructure(ros_name);
  return structure ? ros2msgDefinition(*structure) : "";
}

}  // namespace uampc
