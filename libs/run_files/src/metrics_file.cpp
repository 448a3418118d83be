#include "uampc/run_files/metrics_file.hpp"

#include <filesystem>
#include <stdexcept>
#include <type_traits>

#include "uampc/run_files/json_text.hpp"
#include "uampc/run_files/number_format.hpp"

namespace uampc::run_files {

namespace {

// ---------------------------------------------------------------- the keys, once
// eachField(document part, visit) calls visit(key, field) for every field in the file's order;
// writing and reading both go through it. S is the struct, const when writing.
template <class S, class T>
using Is = std::enable_if_t<std::is_same_v<std::remove_const_t<S>, T>, int>;

constexpr char kRpeKeyPrefix[] = "rpe_";    // + length + "m"
constexpr char kSimTimeKey[] = "sim_time";  // every metrics.json has it

template <class S, class Visit, Is<S, ErrorSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("count", s.count);
  visit("rmse", s.rmse);
  visit("mean", s.mean);
  visit("median", s.median);
  visit("max", s.max);
}

template <class S, class Visit, Is<S, AteSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("unaligned_m", s.unaligned_m);
  visit("aligned_m", s.aligned_m);
}

template <class S, class Visit, Is<S, RpeSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("segment_length_m", s.segment_length_m);
  visit("translation_m", s.translation_m);
  visit("translation_percent", s.translation_percent);
  visit("rotation_deg", s.rotation_deg);
}

template <class S, class Visit, Is<S, SpeedErrorSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("max_m_s", s.max_m_s);
  visit("first_runaway_time", s.first_runaway_time);
}

template <class S, class Visit, Is<S, TrajectorySummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("estimates", s.estimates);
  visit("paired", s.paired);
  visit("unpaired", s.unpaired);
  visit("invalid", s.invalid);
  visit("distance_m", s.distance_m);
  visit("ate", s.ate);
  visit(kRpeKeyPrefix, s.rpe);  // one key per segment length
  visit("speed_error", s.speed_error);
}

template <class S, class Visit, Is<S, CompletenessSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("cmplt", s.cmplt);
  visit("complete_windows", s.complete_windows);
  visit("windows", s.windows);
  visit("total_voxels", s.total_voxels);
  visit("scans", s.scans);
  visit("points", s.points);
  visit("invalid_points", s.invalid_points);
  visit("out_of_range_points", s.out_of_range_points);
  visit("late_scans", s.late_scans);
  visit("invalid_scans", s.invalid_scans);
}

template <class S, class Visit, Is<S, MotorSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("mean_speed", s.mean_speed);
  visit("speed_std", s.speed_std);
  visit("command_change_rms", s.command_change_rms);
  visit("speed_change_rms", s.speed_change_rms);
}

template <class S, class Visit, Is<S, LoSummary> = 0>
void eachField(S& s, Visit&& visit) {
  visit("first_lost_time", s.first_lost_time);
  visit("lost_frames", s.lost_frames);
  visit("rejected_updates", s.rejected_updates);
  visit("velocity_resets", s.velocity_resets);
  visit("frames", s.frames);
  visit("degenerate_frames", s.degenerate_frames);
}

template <class S, class Visit, Is<S, MetricsDocument> = 0>
void eachField(S& s, Visit&& visit) {
  visit(kSimTimeKey, s.sim_time);
  visit("scene_duration", s.scene_duration);
  visit("reached_end", s.reached_end);
  visit("trajectory", s.trajectory);
  visit("cmplt", s.cmplt);
  visit("cmplt_ground_truth", s.cmplt_ground_truth);
  visit("motor", s.motor);
  visit("lo", s.lo);
  visit("run", s.run);  // last: the figures above stay where they always were
}

std::string rpeKey(double segment_length_m) { return kRpeKeyPrefix + formatDouble(segment_length_m) + "m"; }

bool isRpeKey(const std::string& key) {
  const std::string prefix = kRpeKeyPrefix;
  return key.size() > prefix.size() + 1 && key.compare(0, prefix.size(), prefix) == 0 && key.back() == 'm';
}

// ---------------------------------------------------------------- writing
struct Writer {
  Json& json;

  template <class T>
  void operator()(const char* key, const T& part) {
    Json object = Json::object();
    eachField(part, Writer{object});
    json[key] = std::move(object);
  }
  void operator()(const char* key, double value) { json[key] = value; }
  void operator()(const char* key, std::uint64_t value) { json[key] = value; }
  void operator()(const char* key, std::int64_t value) { json[key] = value; }
  void operator()(const char* key, const std::optional<double>& value) {
    if (value) json[key] = *value;
  }
  void operator()(const char* key, const std::optional<bool>& value) {
    if (value) json[key] = *value;
  }
  void operator()(const char*, const std::vector<RpeSummary>& segments) {
    for (const RpeSummary& rpe : segments) (*this)(rpeKey(rpe.segment_length_m).c_str(), rpe);
  }
  void operator()(const char* key, const std::optional<RunInfo>& run) {
    if (run) json[key] = runInfoToJson(*run);
  }
};

// ---------------------------------------------------------------- reading
// What is absent, null or of another type keeps its default.
struct Reader {
  const Json& json;

  const Json* member(const char* key) const {
    const auto found = json.find(key);
    return found == json.end() ? nullptr : &*found;
  }
  template <class T>
  void operator()(const char* key, T& part) {
    if (const Json* object = member(key); object && object->is_object()) eachField(part, Reader{*object});
  }
  void operator()(const char* key, double& value) {
    if (const Json* number = member(key); number && number->is_number()) value = number->get<double>();
  }
  void operator()(const char* key, std::uint64_t& value) {
    if (const Json* number = member(key); number && number->is_number_unsigned()) value = number->get<std::uint64_t>();
  }
  void operator()(const char* key, std::int64_t& value) {
    if (const Json* number = member(key); number && number->is_number_integer()) value = number->get<std::int64_t>();
  }
  void operator()(const char* key, std::optional<double>& value) {
    if (const Json* number = member(key); number && number->is_number()) value = number->get<double>();
  }
  void operator()(const char* key, std::optional<bool>& value) {
    if (const Json* flag = member(key); flag && flag->is_boolean()) value = flag->get<bool>();
  }
  void operator()(const char* key, std::optional<RunInfo>& run) {
    const Json* object = member(key);
    if (!object) return;
    try {
      run = runInfoFromJson(*object, key);
    } catch (const std::runtime_error&) {
      run.reset();  // not whole: as if absent (the figures are what the readers need)
    }
  }
  void operator()(const char*, std::vector<RpeSummary>& segments) {
    for (const auto& [key, object] : json.items()) {
      if (!isRpeKey(key) || !object.is_object()) continue;
      RpeSummary rpe;
      eachField(rpe, Reader{object});
      segments.push_back(rpe);
    }
  }
};

}  // namespace

const RpeSummary* TrajectorySummary::rpeOver(double segment_length_m) const {
  for (const RpeSummary& r : rpe) {
    if (r.segment_length_m == segment_length_m) return &r;
  }
  return nullptr;
}

void writeMetricsFile(const std::string& path, const MetricsDocument& metrics) {
  Json json = Json::object();
  eachField(metrics, Writer{json});
  writeJsonFile(path, json);
}

std::optional<MetricsDocument> readMetricsFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  Json json;
  try {
    json = readJsonFile(path);
  } catch (const std::runtime_error&) {
    return std::nullopt;  // torn: the run did not finish writing it
  }
  if (!json.is_object() || !json.contains(kSimTimeKey)) return std::nullopt;
  MetricsDocument metrics;
  eachField(metrics, Reader{json});
  return metrics;
}

}  // namespace uampc::run_files
