#include "stop_signals.hpp"

#include <signal.h>

#include <atomic>

namespace uampc::app {

namespace {
std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }
}  // namespace

void catchStopSignals() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stopRequested() { return g_stop; }

}  // namespace uampc::app
