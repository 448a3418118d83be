// Topics of the lockstep protocol (docs/dev/time-and-lockstep.md): written and read by the launch
// layer's clock and process groups, and kept free of component ports by the scene validator.
#pragma once

namespace uampc {

constexpr const char* kClockTopic = "/clock";
constexpr const char* kStepAckTopic = "/uampc/lockstep/ack";
// Processes that step themselves tell the launcher how far they are here, every 0.1 s of wall
// time (not every step: the launcher is not in the loop).
constexpr const char* kStepProgressTopic = "/uampc/lockstep/progress";
// Every topic of the protocol starts with this; no component port may use one.
constexpr const char* kLockstepTopicPrefix = "/uampc/lockstep/";

}  // namespace uampc
