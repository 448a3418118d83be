#include "experiment/run_completion.hpp"

#include <cmath>
#include <sstream>

#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_info.hpp"
#include "uampc/runtime/scene.hpp"

namespace uampc::app {

namespace {

std::string withoutTrailingSpace(const std::string& text) {
  const std::size_t end = text.find_last_not_of("\r\n ");
  return end == std::string::npos ? "" : text.substr(0, end + 1);
}

}  // namespace

SceneEnd sceneEndOf(const Scene& scene, std::string* problem) {
  if (scene.clock.mode != ClockMode::kLockstep) {
    *problem =
        "its clock runs in real time: its metrics' time is the wall clock, so an experiment cannot tell a "
        "run that reached its end from one cut short (experiments run lockstep scenes)";
  } else if (!(scene.clock.duration_s > 0.0)) {
    *problem =
        "clock.duration is 0 (until Ctrl-C): its runs would never end on their own (give the experiment a "
        "duration, or the scene a clock.duration)";
  }
  return {scene.clock.duration_s, scene.clock.step.seconds()};
}

bool reachesSceneEnd(double sim_time_s, const SceneEnd& end) {
  return run_files::reachesEnd(sim_time_s, end.duration_s, end.step_s);
}

std::string simTimeOfEnd(double sim_time_s, const SceneEnd& end) {
  std::ostringstream text;
  text << "sim time " << sim_time_s << " s of " << end.duration_s << " s";
  return text.str();
}

RunCompletion runCompletion(const std::string& run_directory, const SceneEnd& end) {
  const std::string failed = withoutTrailingSpace(run_files::readFailedMarker(run_directory));
  const bool done = run_files::readDoneMarker(run_directory).has_value();
  if (!failed.empty()) {
    // Both: two attempts wrote into one directory; neither result can be trusted.
    return {RunState::kFailed, done ? "both a done and a failed marker (" + failed + ")" : failed};
  }
  if (!done) return {RunState::kUnfinished, "not finished"};
  const auto metrics = readRunMetrics(run_directory);
  if (!metrics) return {RunState::kFailed, "a done marker but no readable metrics.json"};
  if (!reachesSceneEnd(metrics->sim_time_s, end)) {
    return {RunState::kFailed, "cut short: " + simTimeOfEnd(metrics->sim_time_s, end)};
  }
  return {RunState::kDone, ""};
}

bool isRunComplete(const std::string& run_directory, const SceneEnd& end) {
  return runCompletion(run_directory, end).state == RunState::kDone;
}

}  // namespace uampc::app
