// Ctrl-C and SIGTERM for the commands that run until stopped (topic, record, play): caught, so
// that the command finishes its work (a summary, a complete file) and exits by itself.
#pragma once

namespace uampc::app {

void catchStopSignals();
// True once SIGINT or SIGTERM arrived; async-signal-safe to set, cheap to poll.
bool stopRequested();

}  // namespace uampc::app
