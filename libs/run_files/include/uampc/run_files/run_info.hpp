// run_info.json: what a run was, for whoever reads its results later. `uampc launch --out DIR`
// writes it when the run starts, from the resolved scene it also writes as DIR/scene.yaml; the
// evaluator copies it into metrics.json as its "run" object. Its keys are named once, in
// run_info.cpp, for writing and reading alike.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "uampc/run_files/json_text.hpp"

namespace uampc::run_files {

struct RunInfo {
  std::string scene_copy;              // the resolved scene's file in the run directory (kSceneCopyFile)
  std::string scene_source;            // the scene file that was launched, absolute
  std::vector<std::string> overrides;  // the --set NAME=VALUE given, in order
  std::string started_utc;             // when the launcher started, "2025-01-31T12:00:00Z"
  std::uint64_t seed = 0;
  int domain_id = 0;
  double duration_s = 0.0;      // the scene's clock.duration, s; 0: until stopped
  std::string uampc_version;    // git describe when uampc was built, as `uampc --version` prints it
  std::string fastdds_version;  // the Fast DDS uampc was built with
  // Every parameter of every component, defaults and rig values included, in the scene's order:
  // instance name -> {"type": ..., "process": ..., "params": {name: value}}.
  Json components = Json::object();
};

Json runInfoToJson(const RunInfo& info);
// Throws std::runtime_error naming `where` and the key when a key is missing or of another type.
RunInfo runInfoFromJson(const Json& json, const std::string& where);

// Whether a lockstep run whose clock reached sim_time_s reached its scene's end, duration_s in
// steps of step_s: its last step may end a step short of the duration, and sim times are sums of
// steps (a rounding short). The one test of a run's end: the evaluator's metrics.json
// "reached_end" and an experiment's done runs (docs/decisions/experiment-run-done.md) both ask it.
// False for NaN.
bool reachesEnd(double sim_time_s, double duration_s, double step_s);

// Throws std::runtime_error naming path on failure.
void writeRunInfoFile(const std::string& path, const RunInfo& info);
// Throws std::runtime_error naming path when the file cannot be read, is not JSON or lacks a key.
RunInfo readRunInfoFile(const std::string& path);

}  // namespace uampc::run_files
