#include "uampc/evaluator/json_writer.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "uampc/evaluator/csv_writer.hpp"

namespace uampc::evaluator {

namespace {

void appendNumber(std::string& out, double value) {
  out += std::isfinite(value) ? formatDouble(value) : "null";  // JSON has no NaN or inf
}

void appendString(std::string& out, const std::string& text) {
  out += '"';
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned>(c));
          out += escaped;
        } else {
          out += c;  // UTF-8 passes through
        }
    }
  }
  out += '"';
}

}  // namespace

JsonObject& JsonObject::put(const std::string& name, Value value) {
  for (auto& member : members_) {
    if (member.first == name) {
      member.second = std::move(value);
      return *this;
    }
  }
  members_.emplace_back(name, std::move(value));
  return *this;
}

JsonObject& JsonObject::set(const std::string& name, double value) { return put(name, value); }
JsonObject& JsonObject::set(const std::string& name, std::int64_t value) {
  return put(name, value);
}
JsonObject& JsonObject::set(const std::string& name, std::uint64_t value) {
  return put(name, value);
}
JsonObject& JsonObject::set(const std::string& name, bool value) { return put(name, value); }
JsonObject& JsonObject::set(const std::string& name, const std::string& value) {
  return put(name, value);
}
JsonObject& JsonObject::set(const std::string& name, const JsonObject& value) {
  return put(name, std::make_shared<const JsonObject>(value));
}
JsonObject& JsonObject::set(const std::string& name, const std::vector<double>& values) {
  return put(name, values);
}

std::string JsonObject::dump(int indent) const {
  std::string out;
  dumpTo(out, indent, 0);
  return out;
}

void JsonObject::dumpTo(std::string& out, int indent, int level) const {
  if (members_.empty()) {
    out += "{}";
    return;
  }
  const std::string inner(static_cast<std::size_t>(indent * (level + 1)), ' ');
  out += "{\n";
  for (std::size_t i = 0; i < members_.size(); ++i) {
    out += inner;
    appendString(out, members_[i].first);
    out += ": ";
    const Value& value = members_[i].second;
    if (const auto* d = std::get_if<double>(&value)) {
      appendNumber(out, *d);
    } else if (const auto* i64 = std::get_if<std::int64_t>(&value)) {
      out += std::to_string(*i64);
    } else if (const auto* u64 = std::get_if<std::uint64_t>(&value)) {
      out += std::to_string(*u64);
    } else if (const auto* b = std::get_if<bool>(&value)) {
      out += *b ? "true" : "false";
    } else if (const auto* s = std::get_if<std::string>(&value)) {
      appendString(out, *s);
    } else if (const auto* object = std::get_if<std::shared_ptr<const JsonObject>>(&value)) {
      (*object)->dumpTo(out, indent, level + 1);
    } else if (const auto* list = std::get_if<std::vector<double>>(&value)) {
      out += '[';
      for (std::size_t k = 0; k < list->size(); ++k) {
        if (k) out += ", ";
        appendNumber(out, (*list)[k]);
      }
      out += ']';
    }
    out += (i + 1 < members_.size()) ? ",\n" : "\n";
  }
  out += std::string(static_cast<std::size_t>(indent * level), ' ');
  out += '}';
}

void writeJson(const std::string& path, const JsonObject& object) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot open JSON file " + path + " for writing");
  out << object.dump() << '\n';
  out.flush();
  if (!out) throw std::runtime_error("error writing JSON file " + path);
}

}  // namespace uampc::evaluator
