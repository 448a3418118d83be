// JSON as the run files print it. nlohmann-json holds the values (in insertion order) and escapes
// the strings; numbers that are doubles are printed shortest round-trip (number_format.hpp), as
// they always were: nlohmann's own printing is not always the shortest (Grisu2) and writes 20 as
// "20.0", which would change every metrics.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace uampc::run_files {

using Json = nlohmann::ordered_json;

// Pretty-printed with indent spaces per level; NaN and infinities as null (JSON has neither);
// lists of plain values on one line ("[1, 2]"), lists holding objects or lists one element a line.
std::string dumpJson(const Json& value, int indent = 2);

// dumpJson(value) and a newline, whole or not at all (writeTextFile, text_file.hpp); throws
// std::runtime_error naming path and the reason on failure.
void writeJsonFile(const std::string& path, const Json& value);

// Throws std::runtime_error naming path when it cannot be read or is not JSON.
Json readJsonFile(const std::string& path);

}  // namespace uampc::run_files
