#include "uampc/run_files/json_text.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "uampc/run_files/number_format.hpp"
#include "uampc/run_files/text_file.hpp"

namespace uampc::run_files {

namespace {

bool isContainer(const Json& value) { return value.is_object() || value.is_array(); }

void dumpTo(std::string& out, const Json& value, int indent, int level) {
  const std::string inner(static_cast<std::size_t>(indent * (level + 1)), ' ');
  const std::string outer(static_cast<std::size_t>(indent * level), ' ');
  if (value.is_object()) {
    if (value.empty()) {
      out += "{}";
      return;
    }
    out += "{\n";
    std::size_t i = 0;
    for (const auto& [key, member] : value.items()) {
      out += inner + Json(key).dump() + ": ";
      dumpTo(out, member, indent, level + 1);
      out += ++i < value.size() ? ",\n" : "\n";
    }
    out += outer + "}";
  } else if (value.is_array()) {
    bool nested = false;
    for (const Json& element : value) nested = nested || isContainer(element);
    out += nested ? "[\n" : "[";
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (nested) out += inner;
      dumpTo(out, value[i], indent, level + 1);
      if (i + 1 < value.size()) out += nested ? ",\n" : ", ";
    }
    out += nested ? "\n" + outer + "]" : "]";
  } else if (value.is_number_float()) {
    const double number = value.get<double>();
    out += std::isfinite(number) ? formatDouble(number) : "null";
  } else {
    // Strings, integers, booleans, null: as nlohmann prints them; invalid UTF-8 is replaced
    // rather than thrown on (a scene name is no reason to lose a run's results).
    out += value.dump(-1, ' ', false, Json::error_handler_t::replace);
  }
}

}  // namespace

std::string dumpJson(const Json& value, int indent) {
  std::string out;
  dumpTo(out, value, indent, 0);
  return out;
}

void writeJsonFile(const std::string& path, const Json& value) { writeTextFile(path, dumpJson(value) + "\n"); }

Json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read JSON file " + path);
  try {
    return Json::parse(in);
  } catch (const Json::parse_error& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
}

}  // namespace uampc::run_files
