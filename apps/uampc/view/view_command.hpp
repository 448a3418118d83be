// `uampc view [--domain N] [--port P] [--address A] [--max-clients N] ...`: serves what a DDS domain publishes to
// Foxglove over its WebSocket protocol, live, until Ctrl-C (docs/user/viewing.md). `uampc launch
// --view` and `uampc play --view` run it beside a run or a replay.
#pragma once

#include "cli/command_set.hpp"
#include "uampc/foxglove/server.hpp"
#include "uampc/listen_address/listen_address.hpp"
#include "uampc/runtime/viewer_process.hpp"

#include <string>

namespace uampc::app {

struct ViewOptions {
  int domain_id = -1;  // -1: ROS_DOMAIN_ID, else 0
  std::string address = "127.0.0.1";
  int port = 8765;
  std::string security_dir;  // a secured domain: DIR of uampc security init (its observer identity)
  double duration_s = 0.0;   // 0: until Ctrl-C or SIGTERM
  ViewerLimits limits;       // 0 in a field: the server's default
};

// The warning for an address other than the loopback one; empty for a loopback address.
std::string exposureWarning(const net::ListenAddress& address, int port);

// Exit codes: 0 when stopped (Ctrl-C, SIGTERM, --duration), 1 when it cannot serve (the port is
// in use, the address is not this machine's, the domain cannot be joined).
int viewCommand(const ViewOptions& options);

// `uampc view` and its options.
void addViewCommand(CommandSet& commands);
// --view, --view-port, --view-address and --view-max-..., for launch and play: a `uampc view` beside
// the run, with the bounds of `uampc view`.
void addViewerOptions(CLI::App* sub, ViewerOptions& options);

}  // namespace uampc::app
