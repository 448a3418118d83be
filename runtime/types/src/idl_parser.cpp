// The IDL subset of ROS 2 message packages (idl_parser.hpp): a recursive-descent parser of the
// tokens idl_lexer.cpp makes of the text.
#include "uampc/runtime/idl_parser.hpp"

#include "idl_lexer.hpp"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <map>
#include <optional>

namespace uampc {
namespace {

using idl::fail;
using idl::Token;

// A type as a declaration names it: an element type, possibly made a sequence (or, by a typedef,
// an array).
struct ParsedType {
  FieldType element;
  FieldDefinition::Collection collection = FieldDefinition::Collection::kSingle;
  std::uint32_t size = 0;
};

struct Literal {
  enum class Kind { kNumber, kString, kBool };
  Kind kind = Kind::kNumber;
  std::string text;
  int line = 0;
};

const std::map<std::string, PrimitiveType>& primitiveKeywords() {
  static const std::map<std::string, PrimitiveType> keywords = {
      {"boolean", PrimitiveType::kBool},   {"octet", PrimitiveType::kByte},    {"char", PrimitiveType::kChar},
      {"int8", PrimitiveType::kInt8},      {"uint8", PrimitiveType::kUInt8},   {"int16", PrimitiveType::kInt16},
      {"uint16", PrimitiveType::kUInt16},  {"int32", PrimitiveType::kInt32},   {"uint32", PrimitiveType::kUInt32},
      {"int64", PrimitiveType::kInt64},    {"uint64", PrimitiveType::kUInt64}, {"float", PrimitiveType::kFloat32},
      {"double", PrimitiveType::kFloat64}, {"short", PrimitiveType::kInt16},
  };
  return keywords;
}

bool isInteger(PrimitiveType type) {
  return type != PrimitiveType::kBool && type != PrimitiveType::kFloat32 && type != PrimitiveType::kFloat64;
}

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& file) : file_(file), lexed_(idl::lexIdl(text, file_)) {}

  IdlFile parse() {
    definitions("", 0);
    IdlFile result;
    result.includes = std::move(lexed_.includes);
    attachConstants();
    result.structs = std::move(structs_);
    return result;
  }

 private:
  // ---- tokens ----
  const Token& peek() const { return lexed_.tokens[next_]; }
  bool peekSymbol(const char* symbol) const { return peek().kind == Token::Kind::kSymbol && peek().text == symbol; }
  bool peekWord(const char* word) const { return peek().kind == Token::Kind::kIdentifier && peek().text == word; }
  bool takeWord(const char* word) {
    if (!peekWord(word)) return false;
    take();
    return true;
  }
  const Token& take() {
    const Token& t = lexed_.tokens[next_];
    if (t.kind != Token::Kind::kEnd) ++next_;
    return t;
  }
  [[noreturn]] void failAt(const Token& t, const std::string& message) const { fail(file_, t.line, message); }
  const Token& expect(const char* symbol) {
    if (!peekSymbol(symbol)) failAt(peek(), std::string("expected '") + symbol + "', got '" + peek().text + "'");
    return take();
  }
  std::string identifier(const char* what) {
    if (peek().kind != Token::Kind::kIdentifier)
      failAt(peek(), std::string("expected ") + what + ", got '" + peek().text + "'");
    return take().text;
  }
  std::uint32_t positiveInteger(const char* what) {
    const Token& t = take();
    char* end = nullptr;
    errno = 0;
    const unsigned long long value = t.kind == Token::Kind::kNumber ? std::strtoull(t.text.c_str(), &end, 0) : 0;
    if (t.kind != Token::Kind::kNumber || *end != '\0' || errno != 0 || value == 0 || value > UINT32_MAX) {
      failAt(t, std::string("expected ") + what + " (a positive integer), got '" + t.text + "'");
    }
    return static_cast<std::uint32_t>(value);
  }

  // ---- definitions ----
  // The definitions of the file (module_line 0) or of the module opened on module_line.
  void definitions(const std::string& scope, int module_line) {
    while (true) {
      if (peek().kind == Token::Kind::kEnd) {
        if (module_line) fail(file_, module_line, "module " + scope + " is not closed with '}'");
        return;
      }
      if (module_line && peekSymbol("}")) return;
      if (peekSymbol(";")) {
        take();
        continue;
      }
      const std::optional<Literal> default_value = annotations();
      const Token& keyword = peek();
      if (peekWord("module")) {
        module(scope);
      } else if (peekWord("struct")) {
        structure(scope);
      } else if (peekWord("typedef")) {
        typeDefinition(scope);
      } else if (peekWord("const")) {
        failAt(keyword, "a constant outside a <Struct>_Constants module");
      } else {
        failAt(keyword, "'" + keyword.text + "' is not part of the IDL subset of ROS 2 messages (module, struct, " +
                            "typedef, const)");
      }
      if (default_value) failAt(keyword, "@default belongs to a struct member");
    }
  }

  void module(const std::string& scope) {
    take();
    const Token& name_token = peek();
    const std::string name = identifier("a module name");
    const std::string inner = scope.empty() ? name : scope + "::" + name;
    expect("{");
    const std::string suffix = "_Constants";
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const std::string owner = name.substr(0, name.size() - suffix.size());
      constants(scope.empty() ? owner : scope + "::" + owner, name_token.line);
    } else {
      definitions(inner, name_token.line);
    }
    expect("}");
    expect(";");
  }

  void structure(const std::string& scope) {
    take();
    const Token& name_token = peek();
    StructDefinition s;
    s.name = (scope.empty() ? "" : scope + "::") + identifier("a struct name");
    s.file = file_;
    s.line = name_token.line;
    if (peekSymbol(";")) return;  // a forward declaration
    if (peekSymbol(":")) failAt(peek(), "struct inheritance is not part of ROS 2 messages");
    expect("{");
    while (!peekSymbol("}")) member(scope, s);
    expect("}");
    expect(";");
    if (s.fields.empty()) failAt(name_token, "struct " + s.name + " has no member");
    structs_.push_back(std::move(s));
  }

  void member(const std::string& scope, StructDefinition& s) {
    const std::optional<Literal> default_value = annotations();
    if (peek().kind == Token::Kind::kEnd) fail(file_, s.line, "struct " + s.name + " is not closed with '}'");
    const ParsedType type = typeSpec(scope);
    const std::size_t first = s.fields.size();
    while (true) {  // "double x, y;" declares two members
      FieldDefinition field;
      field.line = peek().line;
      field.name = identifier("a member name");
      field.type = type.element;
      field.collection = type.collection;
      field.size = type.size;
      if (peekSymbol("[")) arrayDeclarator(field);
      s.fields.push_back(std::move(field));
      if (!peekSymbol(",")) break;
      take();
    }
    const Token& semicolon = expect(";");
    const auto comment = lexed_.comments.find(semicolon.line);
    for (std::size_t i = first; i < s.fields.size(); ++i) {
      if (default_value) s.fields[i].default_value = msgValue(*default_value, s.fields[i].type, s.fields[i].collection);
      if (comment != lexed_.comments.end()) s.fields[i].comment = comment->second;
    }
  }

  void arrayDeclarator(FieldDefinition& field) {
    const Token& bracket = take();
    if (field.collection != FieldDefinition::Collection::kSingle) {
      failAt(bracket, "an array of sequences or arrays is not a ROS 2 type");
    }
    field.collection = FieldDefinition::Collection::kArray;
    field.size = positiveInteger("an array length");
    expect("]");
    if (peekSymbol("[")) failAt(peek(), "multidimensional arrays are not ROS 2 types");
  }

  void typeDefinition(const std::string& scope) {
    take();
    ParsedType type = typeSpec(scope);
    const std::string name = identifier("a typedef name");
    if (peekSymbol("[")) {
      FieldDefinition as_field;
      as_field.collection = type.collection;
      arrayDeclarator(as_field);
      type.collection = as_field.collection;
      type.size = as_field.size;
    }
    expect(";");
    typedefs_[scope.empty() ? name : scope + "::" + name] = type;
  }

  // The body of a module <Struct>_Constants: "const TYPE NAME = VALUE;" lines.
  void constants(const std::string& owner, int line) {
    constant_modules_.emplace(owner, line);
    while (!peekSymbol("}")) {
      annotations();
      if (!peekWord("const")) failAt(peek(), "a _Constants module holds only constants, got '" + peek().text + "'");
      take();
      const Token& type_token = peek();
      const ParsedType type = typeSpec(owner);
      if (type.collection != FieldDefinition::Collection::kSingle || type.element.kind == FieldType::Kind::kStruct) {
        failAt(type_token, "a constant must be a primitive or a string");
      }
      ConstantDefinition c;
      c.name = identifier("a constant name");
      c.type = type.element;
      expect("=");
      c.value = msgValue(literal(), c.type, FieldDefinition::Collection::kSingle);
      expect(";");
      constants_[owner].push_back(std::move(c));
    }
  }

  void attachConstants() {
    for (auto& [owner, list] : constants_) {
      bool attached = false;
      for (StructDefinition& s : structs_) {
        if (s.name != owner) continue;
        s.constants = std::move(list);
        attached = true;
      }
      if (!attached)
        fail(file_, constant_modules_.at(owner), "constants for " + owner + ", which this file does not define");
    }
  }

  // ---- types ----
  ParsedType typeSpec(const std::string& scope) {
    const Token& t = peek();
    if (t.kind != Token::Kind::kIdentifier && !peekSymbol("::")) failAt(t, "expected a type, got '" + t.text + "'");
    if (peekWord("sequence")) return sequence(scope);
    ParsedType type;
    if (peekWord("string")) {
      take();
      type.element.kind = FieldType::Kind::kString;
      if (peekSymbol("<")) {
        take();
        type.element.string_bound = positiveInteger("a string bound");
        expect(">");
      }
      return type;
    }
    if (const std::optional<PrimitiveType> primitive = primitiveKeyword()) {
      type.element.primitive = *primitive;
      return type;
    }
    if (peekWord("wstring") || peekWord("wchar")) failAt(t, "wide characters are not part of ROS 2 messages");
    const std::string name = scopedName();
    if (const ParsedType* alias = typedefNamed(name, scope)) return *alias;
    type.element.kind = FieldType::Kind::kStruct;
    type.element.struct_name = name;
    return type;
  }

  ParsedType sequence(const std::string& scope) {
    take();
    expect("<");
    const Token& inner_token = peek();
    ParsedType type = typeSpec(scope);
    if (type.collection != FieldDefinition::Collection::kSingle) {
      failAt(inner_token, "a sequence of sequences or arrays is not a ROS 2 type");
    }
    type.collection = FieldDefinition::Collection::kSequence;
    if (peekSymbol(",")) {
      take();
      type.size = positiveInteger("a sequence bound");
    }
    expect(">");
    return type;
  }

  // "double", "unsigned long long", ... ; nothing taken when the next word is not one.
  std::optional<PrimitiveType> primitiveKeyword() {
    const std::string& word = peek().text;
    if (peek().kind != Token::Kind::kIdentifier) return std::nullopt;
    if (word == "unsigned") {
      take();
      if (takeWord("short")) return PrimitiveType::kUInt16;
      if (!takeWord("long")) failAt(peek(), "expected 'short' or 'long' after 'unsigned'");
      return takeWord("long") ? PrimitiveType::kUInt64 : PrimitiveType::kUInt32;
    }
    if (word == "long") {
      take();
      if (peekWord("double")) failAt(peek(), "long double is not part of ROS 2 messages");
      return takeWord("long") ? PrimitiveType::kInt64 : PrimitiveType::kInt32;
    }
    const auto found = primitiveKeywords().find(word);
    if (found == primitiveKeywords().end()) return std::nullopt;
    take();
    return found->second;
  }

  std::string scopedName() {
    std::string name;
    if (peekSymbol("::")) take();
    name = identifier("a type name");
    while (peekSymbol("::")) {
      take();
      name += "::" + identifier("a type name");
    }
    return name;
  }

  // A typedef visible from `scope` (innermost scope first), or nullptr.
  const ParsedType* typedefNamed(const std::string& name, std::string scope) const {
    while (true) {
      const auto found = typedefs_.find(scope.empty() ? name : scope + "::" + name);
      if (found != typedefs_.end()) return &found->second;
      if (scope.empty()) return nullptr;
      const auto cut = scope.rfind("::");
      scope = cut == std::string::npos ? "" : scope.substr(0, cut);
    }
  }

  // ---- annotations and values ----
  // Reads the annotations before a definition or member; returns @default's value. @optional and
  // @external change how a sample is serialized, which no ROS 2 type does.
  std::optional<Literal> annotations() {
    std::optional<Literal> default_value;
    while (peekSymbol("@")) {
      take();
      const Token& name_token = peek();
      const std::string name = identifier("an annotation name");
      if (name == "optional" || name == "external") failAt(name_token, "@" + name + " is not part of ROS 2 messages");
      if (!peekSymbol("(")) continue;
      if (name == "default") {
        take();
        if (peekWord("value")) {
          take();
          expect("=");
        }
        default_value = literal();
        expect(")");
      } else {
        skipParenthesized();
      }
    }
    return default_value;
  }

  void skipParenthesized() {
    const Token& open = take();
    int depth = 1;
    while (depth > 0) {
      const Token& t = take();
      if (t.kind == Token::Kind::kEnd) failAt(open, "an annotation's '(' is not closed");
      if (t.kind == Token::Kind::kSymbol) depth += t.text == "(" ? 1 : t.text == ")" ? -1 : 0;
    }
  }

  // A number (with its sign), TRUE/FALSE, or string literals (adjacent ones joined).
  Literal literal() {
    Literal value;
    value.line = peek().line;
    if (peekSymbol("-") || peekSymbol("+")) {
      const std::string sign = take().text;
      if (peek().kind != Token::Kind::kNumber) failAt(peek(), "expected a number after '" + sign + "'");
      value.text = (sign == "-" ? "-" : "") + take().text;
      return value;
    }
    if (peek().kind == Token::Kind::kNumber) {
      value.text = take().text;
      return value;
    }
    if (peekWord("TRUE") || peekWord("FALSE")) {
      value.kind = Literal::Kind::kBool;
      value.text = take().text == "TRUE" ? "true" : "false";
      return value;
    }
    if (peek().kind != Token::Kind::kString) failAt(peek(), "expected a value, got '" + peek().text + "'");
    value.kind = Literal::Kind::kString;
    while (peek().kind == Token::Kind::kString) value.text += take().text;
    return value;
  }

  // A value as a .msg writes it after a field (default) or '=' (constant).
  std::string msgValue(const Literal& value, const FieldType& type, FieldDefinition::Collection collection) const {
    if (collection != FieldDefinition::Collection::kSingle) {
      // rosidl writes an array's default as a string, "(1, 2)"; a .msg writes [1, 2].
      if (value.kind != Literal::Kind::kString) fail(file_, value.line, "an array's default must be a string");
      std::string list = value.text;
      if (!list.empty() && list.front() == '(' && list.back() == ')')
        list = "[" + list.substr(1, list.size() - 2) + "]";
      return list;
    }
    if (type.kind == FieldType::Kind::kString) {
      if (value.kind != Literal::Kind::kString) fail(file_, value.line, "a string value must be a string literal");
      return quoted(value.text);
    }
    if (type.primitive == PrimitiveType::kBool) {
      if (value.kind == Literal::Kind::kBool) return value.text;
      fail(file_, value.line, "a boolean value must be TRUE or FALSE");
    }
    if (value.kind != Literal::Kind::kNumber) fail(file_, value.line, "expected a number, got \"" + value.text + "\"");
    return isInteger(type.primitive) ? integerText(value) : floatText(value);
  }

  // Decimal, whatever base the IDL wrote it in.
  std::string integerText(const Literal& value) const {
    const bool negative = value.text[0] == '-';
    const std::string digits = negative ? value.text.substr(1) : value.text;
    char* end = nullptr;
    errno = 0;
    const unsigned long long magnitude = std::strtoull(digits.c_str(), &end, 0);
    if (*end != '\0' || errno != 0) fail(file_, value.line, "'" + value.text + "' is not an integer");
    return (negative && magnitude != 0 ? "-" : "") + std::to_string(magnitude);
  }

  std::string floatText(const Literal& value) const {
    std::string text = value.text;
    if (!text.empty() && std::string("fFdD").find(text.back()) != std::string::npos) text.pop_back();
    char* end = nullptr;
    std::strtod(text.c_str(), &end);
    if (*end != '\0') fail(file_, value.line, "'" + value.text + "' is not a number");
    return text;
  }

  const std::string file_;
  idl::LexedIdl lexed_;
  std::size_t next_ = 0;
  std::vector<StructDefinition> structs_;
  std::map<std::string, ParsedType> typedefs_;
  std::map<std::string, std::vector<ConstantDefinition>> constants_;  // by the qualified name of their struct
  std::map<std::string, int> constant_modules_;                       // the line of each _Constants module
};

}  // namespace

IdlFile parseIdl(const std::string& text, const std::string& file) { return Parser(text, file).parse(); }

}  // namespace uampc
