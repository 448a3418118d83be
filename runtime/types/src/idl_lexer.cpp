#include "idl_lexer.hpp"

#include <algorithm>
#include <cctype>

#include "uampc/runtime/idl_parser.hpp"

namespace uampc::idl {
namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

class Lexer {
 public:
  Lexer(const std::string& text, const std::string& file) : text_(text), file_(file) {
    while (skipSpaceAndComments()) {
      if (text_[pos_] == '#' && atLineStart()) {
        directive();
      } else {
        tokens_.push_back(token());
      }
    }
    tokens_.push_back({Token::Kind::kEnd, "end of file", line_});
  }

  LexedIdl result() { return {std::move(tokens_), std::move(includes_), std::move(comments_)}; }

 private:
  bool more() const { return pos_ < text_.size(); }
  char at(std::size_t offset) const { return pos_ + offset < text_.size() ? text_[pos_ + offset] : '\0'; }

  // Skips to the next token; false at the end of the text.
  bool skipSpaceAndComments() {
    while (more()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else if (c == '/' && at(1) == '/') {
        const std::size_t end = text_.find('\n', pos_);
        const std::string comment =
            text_.substr(pos_ + 2, end == std::string::npos ? std::string::npos : end - pos_ - 2);
        comments_[line_] = trimmed(comment);
        pos_ = end == std::string::npos ? text_.size() : end;
      } else if (c == '/' && at(1) == '*') {
        const std::size_t end = text_.find("*/", pos_ + 2);
        if (end == std::string::npos) fail(file_, line_, "a /* comment is not closed");
        for (std::size_t i = pos_; i < end; ++i) line_ += text_[i] == '\n';
        pos_ = end + 2;
      } else {
        return true;
      }
    }
    return false;
  }

  bool atLineStart() const {
    for (std::size_t i = pos_; i > 0; --i) {
      const char c = text_[i - 1];
      if (c == '\n') return true;
      if (c != ' ' && c != '\t') return false;
    }
    return true;
  }

  // A preprocessor line: #include is kept; guards and pragmas change nothing a message means.
  void directive() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    const std::string line = trimmed(text_.substr(pos_ + 1, end - pos_ - 1));
    pos_ = end;
    if (line.rfind("include", 0) != 0) return;
    const std::string target = trimmed(line.substr(7));
    const bool quoted = target.size() > 2 && target.front() == '"' && target.back() == '"';
    const bool angled = target.size() > 2 && target.front() == '<' && target.back() == '>';
    if (!quoted && !angled) fail(file_, line_, "#include needs a \"file\" or <file>, got '" + target + "'");
    includes_.push_back(target.substr(1, target.size() - 2));
  }

  Token token() {
    const char c = text_[pos_];
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return word();
    if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && std::isdigit(static_cast<unsigned char>(at(1)))))
      return number();
    if (c == '"') return stringLiteral();
    if (c == '\'') fail(file_, line_, "character literals are not supported");
    if (c == ':' && at(1) == ':') {
      pos_ += 2;
      return {Token::Kind::kSymbol, "::", line_};
    }
    if (std::string("{}<>[];:,=()@-+").find(c) == std::string::npos) {
      fail(file_, line_, std::string("unexpected character '") + c + "'");
    }
    ++pos_;
    return {Token::Kind::kSymbol, std::string(1, c), line_};
  }

  Token word() {
    const std::size_t start = pos_;
    while (more() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
    return {Token::Kind::kIdentifier, text_.substr(start, pos_ - start), line_};
  }

  // Digits, letters (hex digits, exponents, suffixes) and dots; a sign right after an exponent.
  Token number() {
    const std::size_t start = pos_;
    const bool hex = at(0) == '0' && (at(1) == 'x' || at(1) == 'X');
    while (more()) {
      const char c = text_[pos_];
      const bool exponent_sign = !hex && (c == '+' || c == '-') && (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E');
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && !exponent_sign) break;
      ++pos_;
    }
    return {Token::Kind::kNumber, text_.substr(start, pos_ - start), line_};
  }

  Token stringLiteral() {
    const int line = line_;
    std::string value;
    ++pos_;
    while (true) {
      if (!more() || text_[pos_] == '\n') fail(file_, line, "a string literal is not closed");
      const char c = text_[pos_++];
      if (c == '"') break;
      if (c != '\\') {
        value += c;
        continue;
      }
      if (!more()) fail(file_, line, "a string literal is not closed");
      const char escaped = text_[pos_++];
      switch (escaped) {
        case 'n':
          value += '\n';
          break;
        case 't':
          value += '\t';
          break;
        case 'r':
          value += '\r';
          break;
        default:  // \" \\ \' \?
          value += escaped;
      }
    }
    return {Token::Kind::kString, value, line};
  }

  const std::string& text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 1;
  std::vector<Token> tokens_;
  std::vector<std::string> includes_;
  std::map<int, std::string> comments_;
};

}  // namespace

void fail(const std::string& file, int line, const std::string& message) {
  throw IdlError(file + ":" + std::to_string(line) + ": " + message);
}

LexedIdl lexIdl(const std::string& text, const std::string& file) { return Lexer(text, file).result(); }

}  // namespace uampc::idl
