#include "uampc/runtime/viewer_process.hpp"

#include <netdb.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <optional>

#include "uampc/listen_address/listen_address.hpp"

namespace uampc {

std::string viewerAddressProblem(const ViewerOptions& options) {
  // The viewer's own parser: what it would refuse is refused here, before the run starts.
  const std::optional<net::ListenAddress> address = net::parseListenAddress(options.address);
  if (!address) {
    return "cannot serve on " + net::hostAndPort(options.address, options.port) + ": " +
           net::listenAddressError(options.address);
  }
  const std::string where = net::hostAndPort(*address, options.port);
  addrinfo hints{};
  hints.ai_flags = AI_NUMERICHOST | AI_PASSIVE;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(address->numeric.c_str(), std::to_string(options.port).c_str(), &hints, &found) != 0 || !found) {
    return "cannot serve on " + where + ": " + net::listenAddressError(options.address);
  }
  std::string problem;
  const int fd = socket(found->ai_family, SOCK_STREAM, 0);
  const int yes = 1;
  // As the server binds: SO_REUSEADDR, so that a port a previous viewer just left counts as free.
  if (fd < 0 || setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes) != 0 ||
      bind(fd, found->ai_addr, found->ai_addrlen) != 0 || listen(fd, 1) != 0) {
    problem = "cannot serve on " + where + ": " + std::strerror(errno);
  }
  if (fd >= 0) close(fd);
  freeaddrinfo(found);
  return problem;
}

ViewerProcess::ViewerProcess(const ViewerOptions& options, int domain_id, const std::string& security_directory) {
  ChildCommand command;
  command.name = "viewer";
  command.executable = "/proc/self/exe";
  command.argv = {"uampc",     "view",          "--domain", std::to_string(domain_id),
                  "--address", options.address, "--port",   std::to_string(options.port)};
  if (!security_directory.empty()) {
    command.argv.push_back("--security");
    command.argv.push_back(security_directory);
  }
  const auto pass = [&command](const char* option, std::size_t value) {
    if (value == 0) return;
    command.argv.push_back(option);
    command.argv.push_back(std::to_string(value));
  };
  pass("--max-clients", options.limits.max_clients);
  pass("--max-subscriptions-per-client", options.limits.max_subscriptions_per_client);
  pass("--max-queued-bytes-per-client", options.limits.max_queued_bytes_per_client);
  command.exec_failure_message = "uampc: exec of the viewer failed\n";
  child_.start(command);
}

ViewerProcess::~ViewerProcess() {
  if (child_.empty()) return;
  child_.signalAll(SIGTERM);
  if (!child_.waitForExit(ChildProcesses::Clock::now() + std::chrono::seconds(3))) child_.killAll();
}

std::string ViewerProcess::poll() {
  if (!failure_.empty() || child_.empty()) return failure_;
  const auto exit = child_.pollExit();
  if (!exit) return {};
  // It serves until it is stopped, so any end of its own is a failure, exit 0 included.
  failure_ = "the viewer (uampc view) " + describeExitStatus(exit->status) +
             " before the run ended; its own messages above say why";
  return failure_;
}

}  // namespace uampc
