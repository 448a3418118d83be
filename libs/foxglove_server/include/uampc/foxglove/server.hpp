// A read-only Foxglove WebSocket server (protocol.hpp) on websocketpp and standalone asio, serving
// on its own thread. The program that owns it advertises channels and publishes their messages
// from any thread; publish never blocks on a client: each client has a bounded queue per
// subscription (send_queues.hpp), filled by publish and drained by the server's thread as fast as
// the client's socket takes it. A message is held once, however many subscriptions wait for it.
// Clients, their subscriptions and the bytes each may have waiting are bounded; a client over a
// bound, or that keeps misbehaving, gets a status error and is disconnected; the server and its
// owner go on. docs/decisions/live-viewer.md and docs/decisions/viewer-memory-bounds.md say why
// it is built this way.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <set>
#include <string>

#include "uampc/foxglove/protocol.hpp"
#include "uampc/foxglove/send_queues.hpp"

namespace uampc::foxglove {

struct ServerOptions {
  std::string address = "127.0.0.1";  // an IP address to bind ("0.0.0.0": every interface)
  std::uint16_t port = 8765;          // 0: any free port (port() tells which)
  std::string name = "uampc";         // shown by the client
  std::size_t queue_depth = 10;       // messages kept per subscription for a client that lags
  // The bounds on what clients cost (docs/decisions/viewer-memory-bounds.md): a client beyond
  // max_clients, or asking for more than max_subscriptions_per_client, is told and disconnected;
  // a client's messages in waiting and its socket's unwritten bytes together stay within
  // max_client_queued_bytes (its oldest messages are dropped), but for one message larger than that.
  std::size_t max_clients = 16;
  std::size_t max_subscriptions_per_client = 1024;
  std::size_t max_client_queued_bytes = std::size_t(32) << 20;
  // A client's socket is handed a message only while it holds less than this not yet written
  // (the rest waits in its queues, where the oldest can still be dropped); or any one message
  // when it holds nothing.
  std::size_t max_buffered_bytes = std::size_t(8) << 20;
  std::size_t max_client_message_bytes = 1u << 20;  // larger client messages close the connection
  int bad_requests_before_disconnect = 10;          // status errors a client gets before it is dropped
};

struct ServerStatistics {
  std::size_t clients = 0;
  std::uint64_t frames_sent = 0;
  std::uint64_t frames_dropped = 0;  // by all clients' queues, since the start
  std::uint64_t clients_disconnected_for_bad_requests = 0;
  std::uint64_t clients_refused = 0;  // over max_clients, or asking for more than max_subscriptions_per_client
};

class Server {
 public:
  // Binds and starts serving. Throws std::runtime_error naming the address and port when it
  // cannot (not an address as libs/listen_address reads it, in use, not an address of this
  // machine, a privileged port).
  explicit Server(const ServerOptions& options);
  ~Server();  // closes every connection and stops the thread
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  std::uint16_t port() const;

  // A new channel, advertised to every client; `channel.id` is ignored and the new id returned.
  ChannelId advertise(Channel channel);
  // Withdraws a channel: clients are told, and their subscriptions to it end.
  void unadvertise(ChannelId id);

  // One message of a channel, to every client subscribed to it, its payload shared by all of
  // them. time_ns: the message's time in the server's time base (broadcastTime's). Any thread;
  // never blocks on a client.
  void publish(ChannelId channel, std::uint64_t time_ns, Payload payload);
  // The same for a latched channel (a transient-local topic): its latest `keep` messages are kept
  // too, and every later subscription to it starts with them, as a late DDS reader would get them.
  void publishLatched(ChannelId channel, std::uint64_t time_ns, Payload payload, std::size_t keep);
  // Forgets what publishLatched kept of a channel: its owner stopped reading it, and the next
  // reader brings the kept samples anew.
  void forgetLatched(ChannelId channel);
  // The server's current time, to every client (skipped for a client whose socket is full).
  void broadcastTime(std::uint64_t time_ns);

  // Channels that at least one client subscribes to: what the owner has to read.
  std::set<ChannelId> subscribedChannels() const;
  ServerStatistics statistics() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace uampc::foxglove
