#include "uampc/run_files/run_info.hpp"

#include <stdexcept>
#include <type_traits>

namespace uampc::run_files {

namespace {

// The keys, once: eachInfoField(info, visit) calls visit(key, field) in the file's order; writing and
// reading both go through it. I is RunInfo, const when writing.
template <class I, class Visit>
void eachInfoField(I& info, Visit&& visit) {
  visit("scene", info.scene_copy);
  visit("scene_source", info.scene_source);
  visit("overrides", info.overrides);
  visit("started_utc", info.started_utc);
  visit("seed", info.seed);
  visit("domain_id", info.domain_id);
  visit("duration_s", info.duration_s);
  visit("uampc_version", info.uampc_version);
  visit("fastdds_version", info.fastdds_version);
  visit("components", info.components);
}

struct InfoReader {
  const Json& json;
  const std::string& where;

  template <class T>
  void operator()(const char* key, T& field) const {
    const auto found = json.find(key);
    if (found == json.end()) throw std::runtime_error(where + ": no key '" + key + "'");
    try {
      if constexpr (std::is_same_v<T, Json>) {
        if (!found->is_object()) throw std::runtime_error("not an object");
        field = *found;
      } else if constexpr (std::is_integral_v<T>) {
        // nlohmann would convert 3.7 or -1 silently.
        if (!found->is_number_integer() || (std::is_unsigned_v<T> && !found->is_number_unsigned()))
          throw std::runtime_error("not a whole number");
        field = found->template get<T>();
      } else {
        field = found->template get<T>();
      }
    } catch (const std::exception&) {
      throw std::runtime_error(where + ": '" + key + "' is " + found->dump() + ", not of the expected type");
    }
  }
};

}  // namespace

Json runInfoToJson(const RunInfo& info) {
  Json json = Json::object();
  eachInfoField(info, [&json](const char* key, const auto& field) { json[key] = field; });
  return json;
}

RunInfo runInfoFromJson(const Json& json, const std::string& where) {
  if (!json.is_object()) throw std::runtime_error(where + ": not a JSON object");
  RunInfo info;
  eachInfoField(info, InfoReader{json, where});
  return info;
}

void writeRunInfoFile(const std::string& path, const RunInfo& info) { writeJsonFile(path, runInfoToJson(info)); }

RunInfo readRunInfoFile(const std::string& path) { return runInfoFromJson(readJsonFile(path), path); }

bool reachesEnd(double sim_time_s, double duration_s, double step_s) {
  constexpr double kRounding = 1e-6;  // s
  return sim_time_s + step_s + kRounding >= duration_s;
}

}  // namespace uampc::run_files
