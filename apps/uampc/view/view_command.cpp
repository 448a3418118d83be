#include "view/view_command.hpp"

#include <chrono>
#include <iostream>
#include <thread>

#include "topic/topic_discovery.hpp"
#include "uampc/foxglove/server.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/stop_signals.hpp"
#include "view/topic_bridge.hpp"

namespace uampc::app {

namespace {

// Discovery and the clock are followed this often; samples go out as they arrive, not at this pace.
constexpr auto kUpdatePeriod = std::chrono::milliseconds(20);

bool isLoopback(const std::string& address) {
  return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

void reportClients(std::size_t& known, const foxglove::ServerStatistics& now) {
  if (now.clients == known) return;
  std::cerr << "uampc view: " << now.clients << " client(s) connected\n";
  known = now.clients;
}

}  // namespace

std::string exposureWarning(const std::string& address, int port) {
  if (isLoopback(address)) return {};
  return "uampc view: serving on " + address + ":" + std::to_string(port) +
         ", not only this machine: anyone who reaches it sees every topic of the domain";
}

int viewCommand(const ViewOptions& options) {
  try {
    const int domain = options.domain_id >= 0 ? options.domain_id : rosDomainIdFromEnvironment().value_or(0);
    catchStopSignals();
    foxglove::ServerOptions server_options;
    server_options.address = options.address == "localhost" ? "127.0.0.1" : options.address;
    server_options.port = static_cast<std::uint16_t>(options.port);
    server_options.name = "uampc view (DDS domain " + std::to_string(domain) + ")";
    foxglove::Server server(server_options);
    if (const std::string warning = exposureWarning(options.address, options.port); !warning.empty()) {
      std::cerr << warning << "\n";
    }
    TopicDiscovery discovery(domain, checkedSecurityIdentity(options.security_dir, kObserverIdentity));
    TopicBridge bridge(discovery, server);
    std::cerr << "uampc view: serving DDS domain " << domain << " on ws://" << options.address << ":" << server.port()
              << " (Foxglove: Open connection; Ctrl-C stops)" << std::endl;
    const auto started = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
    std::size_t clients = 0;
    while (!stopRequested() && (options.duration_s <= 0 || elapsed() < options.duration_s)) {
      bridge.update();
      reportClients(clients, server.statistics());
      std::this_thread::sleep_for(kUpdatePeriod);
    }
    const foxglove::ServerStatistics s = server.statistics();
    std::cerr << "uampc view: stopped; " << bridge.channelsOffered() << " topic(s) offered, " << s.frames_sent
              << " message(s) sent, " << s.frames_dropped << " dropped for clients that read too slowly\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "uampc view: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace uampc::app
