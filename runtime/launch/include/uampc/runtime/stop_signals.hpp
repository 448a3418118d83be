// Ctrl-C, SIGTERM and SIGHUP for every uampc command that runs until stopped (launch, run-process, clock,
// topic, record, play, experiment): caught, so that the command finishes its work (processes
// stopped, a complete file, a summary) and exits by itself.
#pragma once

#include <atomic>

namespace uampc {

void catchStopSignals();
// True once SIGINT, SIGTERM or SIGHUP arrived; async-signal-safe to set, cheap to poll.
bool stopRequested();
// The flag itself, for code that polls it (the lockstep clock, a process group, the experiment runner).
const std::atomic<bool>& stopFlag();
// The last of these signals that arrived (SIGINT: the terminal's Ctrl-C), 0 before any.
int lastStopSignal();

}  // namespace uampc
