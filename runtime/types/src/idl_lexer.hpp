// The lexer of the IDL parser (idl_parser.cpp): the tokens of an IDL file, with the targets of its
// #include lines and its // comments by line (a field's comment documents it in the definition).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace uampc::idl {

struct Token {
  enum class Kind { kIdentifier, kNumber, kString, kSymbol, kEnd };
  Kind kind = Kind::kEnd;
  std::string text;  // a string literal without its quotes, escapes resolved
  int line = 0;
};

// Throws IdlError "file:line: message".
[[noreturn]] void fail(const std::string& file, int line, const std::string& message);

struct LexedIdl {
  std::vector<Token> tokens;            // the last one is kEnd
  std::vector<std::string> includes;    // as #include names them
  std::map<int, std::string> comments;  // the text of the // comment on each line that has one
};

LexedIdl lexIdl(const std::string& text, const std::string& file);

}  // namespace uampc::idl
