#include "uampc/runtime/stop_signals.hpp"

#include <signal.h>

namespace uampc {

namespace {
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

void onSignal(int signal) {
  g_signal = signal;
  g_stop = true;
}
}  // namespace

void catchStopSignals() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);  // a closed terminal: stop cleanly, as on Ctrl-C
}

bool stopRequested() { return g_stop; }
const std::atomic<bool>& stopFlag() { return g_stop; }
int lastStopSignal() { return g_signal; }

}  // namespace uampc
