// The live viewer beside a run or a replay (`uampc launch --view`, `uampc play --view`): a child
// `uampc view` on the run's DDS domain, so that whatever a viewer's clients do stays outside the
// processes of the run (docs/decisions/live-viewer.md). It is stopped with the run; if it ends
// early, the run fails (docs/decisions/run-fails-with-its-viewer.md).
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "uampc/runtime/child_processes.hpp"

namespace uampc {

// What the viewer's clients may cost (docs/decisions/viewer-memory-bounds.md); 0: the viewer's own
// default, which `uampc view --help` prints.
struct ViewerLimits {
  std::size_t max_clients = 0;
  std::size_t max_subscriptions_per_client = 0;
  std::size_t max_queued_bytes_per_client = 0;
};

struct ViewerOptions {
  bool enabled = false;
  std::string address = "127.0.0.1";
  int port = 8765;
  ViewerLimits limits;
};

// Why the viewer could not serve on its address and port (not an address as the viewer reads it,
// libs/listen_address; in use; not an address of this machine); empty when it can. Checked before
// a run starts, so that a run with --view does not start without its viewer.
std::string viewerAddressProblem(const ViewerOptions& options);

class ViewerProcess {
 public:
  // Starts `uampc view --domain D --address A --port P [--security DIR]` (this executable), with
  // the limits that are set.
  ViewerProcess(const ViewerOptions& options, int domain_id, const std::string& security_directory);
  ~ViewerProcess();  // SIGTERM, then SIGKILL if it has not ended within 3 s
  ViewerProcess(const ViewerProcess&) = delete;
  ViewerProcess& operator=(const ViewerProcess&) = delete;

  // Why the run must fail: the viewer ended before it was stopped (how it ended, named); empty
  // while it serves. Never blocks.
  std::string poll();

 private:
  ChildProcesses child_;
  std::string failure_;
};

}  // namespace uampc
