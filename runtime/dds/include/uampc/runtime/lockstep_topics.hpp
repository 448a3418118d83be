// Topics of the lockstep protocol (docs/dev/time-and-lockstep.md): written and read by the launch
// layer's clock and process groups, and kept free of component ports by the scene validator.
#pragma once

#include <string_view>

namespace uampc {

constexpr const char* kClockTopic = "/clock";
constexpr const char* kStepAckTopic = "/uampc/lockstep/ack";
// Processes that step themselves tell the launcher how far they are here, every 0.1 s of wall
// time (not every step: the launcher is not in the loop).
constexpr const char* kStepProgressTopic = "/uampc/lockstep/progress";
// Every topic of the protocol starts with this; no component port may use one.
constexpr const char* kLockstepTopicPrefix = "/uampc/lockstep/";

// A topic of the protocol itself (not /clock, which outside tools read too). A recording of one
// replayed onto a live domain would reach that run's clock as another run's
// (docs/decisions/replay-leaves-lockstep-topics.md).
inline bool isLockstepProtocolTopic(std::string_view topic) { return topic.rfind(kLockstepTopicPrefix, 0) == 0; }

// What a player never publishes: the protocol's topics and /clock, which a run on the domain
// writes itself (a player makes its own /clock on request, from the recording's time line).
inline bool isLockstepRunTopic(std::string_view topic) {
  return topic == kClockTopic || isLockstepProtocolTopic(topic);
}

}  // namespace uampc
