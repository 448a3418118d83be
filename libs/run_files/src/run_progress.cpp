#include "uampc/run_files/run_progress.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "uampc/run_files/json_text.hpp"

namespace uampc::run_files {

namespace {

template <class S, class Visit>
void eachProgressField(S& p, Visit&& visit) {
  visit("sim_s", p.sim_s);
  visit("total_s", p.total_s);
  visit("wall_s", p.wall_s);
  visit("finished", p.finished);
}

}  // namespace

void writeRunProgress(const std::string& path, const RunProgress& progress) {
  Json json = Json::object();
  eachProgressField(progress, [&json](const char* key, const auto& value) { json[key] = value; });
  writeJsonFile(path, json);  // whole or not at all: a reader never sees half a file
}

std::optional<RunProgress> readRunProgress(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  RunProgress progress;
  try {
    const Json json = readJsonFile(path);
    bool complete = json.is_object();
    eachProgressField(progress, [&](const char* key, auto& value) {
      using Field = std::remove_reference_t<decltype(value)>;
      const auto found = complete ? json.find(key) : json.end();
      const bool fits = found != json.end() && (std::is_same_v<Field, bool> ? found->is_boolean() : found->is_number());
      if (fits)
        value = found->template get<Field>();
      else
        complete = false;
    });
    if (!complete) return std::nullopt;
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
  return progress;
}

}  // namespace uampc::run_files
