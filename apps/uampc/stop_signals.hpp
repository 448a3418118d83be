// Ctrl-C and SIGTERM for the commands that run until stopped (topic, record, play, experiment):
// caught, so that the command finishes its work (a summary, a complete file, runs stopped) and
// exits by itself.
#pragma once

#include <atomic>

namespace uampc::app {

void catchStopSignals();
// True once SIGINT or SIGTERM arrived; async-signal-safe to set, cheap to poll.
bool stopRequested();
// The flag itself, for code that polls it (the experiment runner).
const std::atomic<bool>& stopFlag();

}  // namespace uampc::app
