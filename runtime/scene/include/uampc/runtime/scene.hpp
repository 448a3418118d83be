// A scene: one YAML file that says which components run, with which parameters, wired to which
// topics, under which clock, in which processes (docs/dev/architecture.md section 5). See
// docs/user/scenes.md for the format. loadScene() validates everything before anything starts and
// reports every problem with file:line:column.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/runtime/component_library.hpp"
#include "uampc/runtime/parameter.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc {

struct SourceLocation {
  std::string file;  // or "--set" for command-line overrides
  int line = 0;      // 1-based; 0 when unknown
  int column = 0;    // 1-based
  std::string str() const;
};

// All problems found in a scene, each "file:line:column: error: message".
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<std::string> messages);
  const std::vector<std::string>& messages() const { return messages_; }
  const char* what() const noexcept override;  // the messages, one per line

 private:
  std::vector<std::string> messages_;  // with control bytes escaped (logger.hpp, printableText)
  std::string text_;
};

enum class ClockMode { kLockstep, kRealtime };
enum class CrashPolicy { kStop, kRestart };

struct ClockSettings {
  ClockMode mode = ClockMode::kLockstep;
  Time step = Time{5'000'000};  // lockstep step, 5 ms: one encoder period at 200 Hz
  double duration_s = 0.0;      // sim (lockstep) or wall (real-time) seconds; 0: until Ctrl-C
  double ack_timeout_s = 60.0;  // wall seconds one lockstep step may take before the run is hung
  // Wall seconds DDS discovery may take at the start: at least 30 s, whatever ack_timeout says, so
  // that a short ack_timeout does not fail a start on a busy machine.
  double startupTimeout() const { return ack_timeout_s > 30.0 ? ack_timeout_s : 30.0; }
  double real_time_factor = 0.0;  // lockstep pacing: 0 = as fast as possible, 1 = real time
  // Lockstep: each process group steps itself, from the others' acknowledgements, and the launcher
  // only watches (docs/dev/time-and-lockstep.md); false: the launcher's clock ticks every step.
  bool in_process = true;
};

struct ComponentInstance {
  std::string name;
  std::string type;
  std::string process = "main";
  SourceLocation location;
  std::map<std::string, ParameterValue> params;  // every declared parameter, defaults filled in
  std::map<std::string, std::string> topics;     // every port -> its topic after remapping
  std::vector<PortSpec> ports;  // the declared ports, then those decided by the scene (scenePorts)
  const PortSpec* findPort(const std::string& port) const;
  const ComponentLibrary* library = nullptr;
};

struct Scene {
  std::string file;       // absolute path
  std::string directory;  // its folder; relative paths in the scene are from here
  std::string name;
  int domain_id = 0;
  std::string dds_profile;  // absolute path of a Fast DDS XML profile file, or empty
  // DDS Security (security: {directory: DIR}): the absolute path of what `uampc security init`
  // wrote, or empty when the run is not secured (dds_security.hpp).
  std::string security_directory;
  std::uint64_t seed = 1;
  ClockSettings clock;
  CrashPolicy on_crash = CrashPolicy::kStop;
  int max_restarts = 3;
  // Topics published outside the scene (external_topics:), such as a LiDAR driver's on a rig: read
  // by the scene's components, written by none of them, and neither an error nor a warning.
  std::vector<std::string> external_topics;
  // Outputs the scene writes for viewers and tools (outputs_for_tools:): that no component of the
  // scene reads them is expected, not a warning (as for ports declared PortSpec::forViewers).
  std::vector<std::string> outputs_for_tools;
  // Inputs the scene leaves unfed on purpose (unused_inputs:): read by components that do without
  // them here (the LO's imu with use_imu: false), written by nobody, and neither an error nor a
  // warning. Listing a topic a component writes, or one nobody reads, is an error.
  std::vector<std::string> unused_inputs;
  std::vector<ComponentInstance> components;  // in file order
  // The rig's parameters (ParameterSpec::rig) that the scene's components declare, resolved: the
  // rig: block's values, defaults filled in. Each such component has the same value in its params.
  std::map<std::string, ParameterValue> rig;
  // "file:line:column: warning: ..." for what may be a mistake but need not be (an input no
  // component writes, an output nobody reads); launch and validate print them.
  std::vector<std::string> warnings;

  std::vector<std::string> processes() const;  // in order of first appearance
  // Whether the scene's process groups step themselves, without the launcher's clock (lockstep
  // with clock.in_process).
  bool processesStepThemselves() const;
  // DDS readers of a topic over the whole scene: one per process and QoS for its typed inputs,
  // one per serialized input (PortSpec::serialized).
  int readersOf(const std::string& topic) const;
  // Output ports (each its own DDS writer) bound to a topic, over the whole scene.
  int writersOf(const std::string& topic) const;
  const ComponentInstance* find(const std::string& name) const;
};

// "component.param=value", "clock.key=value" or "key=value" (top-level keys such as seed).
struct Override {
  std::string text;  // as given, for messages
  std::vector<std::string> path;
  std::string value;  // YAML scalar or flow text
};
Override parseOverride(const std::string& text);  // throws SceneError on bad syntax

// Reads the scene at `path` with the scenes it extends (`extends:`), applies the overrides and
// validates it all; throws SceneError with every error found. check_security false: the security
// directory is not checked (`uampc security init` reads the scene to make it).
Scene loadScene(const std::string& path, const std::vector<Override>& overrides, ComponentCatalog& catalog,
                bool check_security = true);

}  // namespace uampc
