// QoS presets (docs/dev/architecture.md section 4). A port names a preset; the runtime turns it
// into DDS QoS. In lockstep mode every preset becomes reliable keep-all, so that no sample the loop
// depends on is lost; transient-local stays transient-local.
#pragma once

namespace uampc {

enum class QosPreset {
  kSensor,   // streams: best-effort keep-last 5 in real time
  kControl,  // commands and states: reliable keep-last 10
  kLatched,  // maps, configuration: reliable transient-local, the last 100 samples kept for late joiners
};

// Samples of a latched topic kept for late joiners: a latched message sent in more chunks than this
// loses its first ones.
inline constexpr int kLatchedHistoryDepth = 100;

const char* toString(QosPreset preset);

}  // namespace uampc
