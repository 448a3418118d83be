#include "view/view_command.hpp"

#include <malloc.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "cli/command_set.hpp"
#include "topic/topic_discovery.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/foxglove/server.hpp"
#include "uampc/listen_address/listen_address.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/stop_signals.hpp"
#include "view/topic_bridge.hpp"

namespace uampc::app {

namespace {

// Discovery and the clock are followed this often; samples go out as they arrive, not at this pace.
constexpr auto kUpdatePeriod = std::chrono::milliseconds(20);

void reportClients(std::size_t& known, const foxglove::ServerStatistics& now) {
  if (now.clients == known) return;
  // What the clients that left had waiting was freed into glibc's arenas, which keep it (hundreds
  // of MB after many clients, measured in docs/user/viewing.md): given back to the system here.
  if (now.clients < known) malloc_trim(0);
  std::cerr << "uampc view: " << now.clients << " client(s) connected\n";
  known = now.clients;
}

// "32 MiB" for a whole number of MiB, else "N bytes".
std::string byteCount(std::size_t bytes) {
  constexpr std::size_t kMiB = std::size_t(1) << 20;
  return bytes % kMiB == 0 ? std::to_string(bytes / kMiB) + " MiB" : std::to_string(bytes) + " bytes";
}

// The bounds on what clients cost, as --PREFIXmax-clients ...; a client over one is told in a status
// error and disconnected. The defaults printed are the server's.
std::vector<CLI::Option*> addLimitOptions(CLI::App* sub, const std::string& prefix, ViewerLimits& limits) {
  const foxglove::ServerOptions defaults;
  std::vector<CLI::Option*> added;
  added.push_back(sub->add_option("--" + prefix + "max-clients", limits.max_clients,
                                  "Clients served at once (default " + std::to_string(defaults.max_clients) +
                                      "); one more is told so and disconnected.")
                      ->check(CLI::Range(std::size_t(1), std::size_t(10000)))
                      ->type_name("N"));
  added.push_back(sub->add_option("--" + prefix + "max-subscriptions-per-client", limits.max_subscriptions_per_client,
                                  "Subscriptions one client may hold (default " +
                                      std::to_string(defaults.max_subscriptions_per_client) +
                                      "); a client that asks for more is told so and\ndisconnected.")
                      ->check(CLI::Range(std::size_t(1), std::size_t(1000000)))
                      ->type_name("N"));
  added.push_back(
      sub->add_option(
             "--" + prefix + "max-queued-bytes-per-client", limits.max_queued_bytes_per_client,
             "Bytes one client may have waiting, in its queues and its socket together (default " +
                 std::to_string(defaults.max_client_queued_bytes >> 20) +
                 " MiB;\nsuffixes kB, MB, KiB, MiB, ...): beyond that its oldest messages are dropped, as for a\n"
                 "client that reads too slowly; one message larger than that still goes, alone.")
          ->transform(CLI::AsSizeValue(true))
          ->check(CLI::Range(std::size_t(1) << 16, std::size_t(1) << 40))
          ->type_name("B"));
  return added;
}

}  // namespace

std::string exposureWarning(const net::ListenAddress& address, int port) {
  if (address.loopback) return {};
  return "uampc view: serving on " + net::hostAndPort(address, port) +
         ", not only this machine: anyone who reaches it sees every topic of the domain";
}

int viewCommand(const ViewOptions& options) {
  try {
    const int domain = options.domain_id >= 0 ? options.domain_id : rosDomainIdFromEnvironment().value_or(0);
    catchStopSignals();
    // The parser the launcher checks --view-address with, so that both read an address alike.
    const std::optional<net::ListenAddress> address = net::parseListenAddress(options.address);
    if (!address) {
      throw std::runtime_error("cannot serve on " + net::hostAndPort(options.address, options.port) + ": " +
                               net::listenAddressError(options.address));
    }
    foxglove::ServerOptions server_options;
    server_options.address = address->numeric;
    server_options.port = static_cast<std::uint16_t>(options.port);
    server_options.name = "uampc view (DDS domain " + std::to_string(domain) + ")";
    const ViewerLimits& limits = options.limits;
    if (limits.max_clients > 0) server_options.max_clients = limits.max_clients;
    if (limits.max_subscriptions_per_client > 0) {
      server_options.max_subscriptions_per_client = limits.max_subscriptions_per_client;
    }
    if (limits.max_queued_bytes_per_client > 0) {
      server_options.max_client_queued_bytes = limits.max_queued_bytes_per_client;
    }
    foxglove::Server server(server_options);
    if (const std::string warning = exposureWarning(*address, server.port()); !warning.empty()) {
      std::cerr << warning << "\n";
    }
    TopicDiscovery discovery(domain, checkedSecurityIdentity(options.security_dir, kObserverIdentity));
    TopicBridge bridge(discovery, server);
    std::cerr << "uampc view: serving DDS domain " << domain << " on " << net::webSocketUrl(*address, server.port())
              << " (Foxglove: Open connection; Ctrl-C stops)" << std::endl;
    std::cerr << "uampc view: at most " << server_options.max_clients << " clients, "
              << server_options.max_subscriptions_per_client << " subscriptions and "
              << byteCount(server_options.max_client_queued_bytes) << " waiting per client\n";
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
              << " message(s) sent, " << s.frames_dropped << " dropped for clients that read too slowly, "
              << s.clients_refused << " client(s) refused over a bound\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "uampc view: error: " << e.what() << "\n";
    return 1;
  }
}

void addViewerOptions(CLI::App* sub, ViewerOptions& o) {
  CLI::Option* view = sub->add_flag(
      "--view", o.enabled, "Serve the topics live to Foxglove (WebSocket, ws://127.0.0.1:8765; docs/user/viewing.md).");
  sub->add_option("--view-port", o.port, "The viewer's TCP port (default 8765).")
      ->check(CLI::Range(1, 65535))
      ->type_name("P");
  sub->add_option("--view-address", o.address,
                  "The address the viewer binds (default 127.0.0.1, this machine only; an IPv4 address as four\n"
                  "numbers, an IPv6 one, or localhost, refused before anything starts otherwise; another address\n"
                  "is warned about: anyone who reaches it sees every topic). A viewer that fails fails the run.")
      ->type_name("A");
  for (CLI::Option* limit : addLimitOptions(sub, "view-", o.limits)) limit->needs(view);
}

void addViewCommand(CommandSet& commands) {
  auto options = std::make_shared<ViewOptions>();
  ViewOptions& o = *options;
  CLI::App* sub =
      commands.add("view",
                   "uampc view [--domain N] [--port P] [--address A] [--security DIR] [--duration S]\n"
                   "[--max-clients N] [--max-subscriptions-per-client N] [--max-queued-bytes-per-client B]",
                   "Serve what a DDS domain publishes (a rig, another machine's run, a replay) live to Foxglove over\n"
                   "its WebSocket protocol: every ROS topic with its schema, read from DDS only while a client\n"
                   "subscribes; the domain's /clock sets the clients' time. Ctrl-C stops it. What clients cost is\n"
                   "bounded: at most --max-clients of them, each with --max-subscriptions-per-client and\n"
                   "--max-queued-bytes-per-client waiting; the bound on its memory is in docs/user/viewing.md.");
  sub->add_option("--domain", o.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0).")
      ->check(CLI::Range(0, uampc::kMaxDomainId))
      ->type_name("N");
  sub->add_option("--port", o.port, "TCP port (default 8765; 0: any free port, printed).")
      ->check(CLI::Range(0, 65535))
      ->type_name("P");
  sub->add_option("--address", o.address,
                  "Address to bind (default 127.0.0.1, this machine only): an IPv4 address as four numbers, an\n"
                  "IPv6 one (::1, served as ws://[::1]:P) or localhost; another address is warned about.")
      ->type_name("A");
  sub->add_option("--security", o.security_dir,
                  "Join a secured domain with the observer identity of DIR (uampc security init), which may\n"
                  "read every topic.")
      ->type_name("DIR");
  sub->add_option("--duration", o.duration_s, "Stop after S seconds (default: at Ctrl-C).")
      ->check(command_line::kFiniteNonNegative)
      ->type_name("S");
  addLimitOptions(sub, "", o.limits);
  commands.onRun(sub, [options] { return viewCommand(*options); });
}

}  // namespace uampc::app
