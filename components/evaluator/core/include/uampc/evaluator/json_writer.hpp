// A small JSON writer for metrics: an object of named numbers, strings, booleans and objects.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace uampc::evaluator {

class JsonObject {
 public:
  // Setting a name again replaces its value and keeps its place; names keep insertion order.
  JsonObject& set(const std::string& name, double value);  // NaN and inf are written as null
  JsonObject& set(const std::string& name, std::int64_t value);
  JsonObject& set(const std::string& name, std::uint64_t value);
  JsonObject& set(const std::string& name, int value) { return set(name, std::int64_t{value}); }
  JsonObject& set(const std::string& name, bool value);
  JsonObject& set(const std::string& name, const std::string& value);
  JsonObject& set(const std::string& name, const char* value) {
    return set(name, std::string(value));
  }
  JsonObject& set(const std::string& name, const JsonObject& value);
  // A list of numbers (NaN and inf as null).
  JsonObject& set(const std::string& name, const std::vector<double>& values);

  bool empty() const { return members_.empty(); }
  // Pretty-printed with indent spaces per level; doubles shortest round-trip.
  std::string dump(int indent = 2) const;

 private:
  using Value = std::variant<double, std::int64_t, std::uint64_t, bool, std::string,
                             std::shared_ptr<const JsonObject>, std::vector<double>>;
  JsonObject& put(const std::string& name, Value value);
  void dumpTo(std::string& out, int indent, int level) const;
  std::vector<std::pair<std::string, Value>> members_;
};

// Writes object.dump() and a newline. Throws std::runtime_error naming path on failure.
void writeJson(const std::string& path, const JsonObject& object);

}  // namespace uampc::evaluator
