#include "stop_signals.hpp"

#include <signal.h>

namespace uampc::app {

namespace {
std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }
}  // namespace

void catchStopSignals() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stopRequested() { return g_stop; }
const std::atomic<bool>& stopFlag() { return g_stop; }

}  // namespace uampc::app
