#include "uampc/foxglove/server.hpp"

// Standalone asio (libasio-dev), not Boost's.
#define ASIO_STANDALONE
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "uampc/foxglove/latched_messages.hpp"
#include "uampc/foxglove/send_queues.hpp"
#include "uampc/listen_address/listen_address.hpp"

namespace uampc::foxglove {

namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

constexpr long kPumpPeriodMs = 10;          // queues are drained at least this often
constexpr long kDropReportPeriodMs = 2000;  // a lagging client hears of its drops at most this often
constexpr long kCloseGraceMs = 200;         // for close frames to leave before the thread stops

struct Client {
  Client(std::size_t depth, std::size_t max_bytes) : queues(depth, max_bytes) {}
  SendQueues queues;
  std::map<SubscriptionId, ChannelId> subscriptions;
  int bad_requests = 0;
  bool closing = false;  // disconnected (bad requests, a bound); gone when its close handler runs
  // Its socket's unwritten bytes as the server's thread last saw them (every pump), for publish
  // on other threads, where websocketpp's count may not be read. Messages are sent on that thread
  // and it is updated after them, so it is off by what the socket wrote since (then it is higher
  // than the count) and by the owner's advertisements, a few KB.
  std::size_t socket_bytes = 0;
};

}  // namespace

class Server::Impl {
 public:
  explicit Impl(const ServerOptions& options) : options_(options) {
    server_.clear_access_channels(websocketpp::log::alevel::all);
    // A client that vanishes mid-message is normal for a viewer; its transport errors are not news.
    server_.clear_error_channels(websocketpp::log::elevel::all);
    server_.init_asio();
    server_.set_reuse_addr(true);
    server_.set_max_message_size(options_.max_client_message_bytes);
    server_.set_validate_handler([this](Handle h) { return validate(h); });
    server_.set_open_handler([this](Handle h) { onOpen(h); });
    server_.set_close_handler([this](Handle h) { onGone(h); });
    server_.set_fail_handler([this](Handle h) { onGone(h); });
    server_.set_message_handler([this](Handle h, WsServer::message_ptr m) { onMessage(h, m); });
    listen();
    server_.start_accept();
    schedulePump();
    scheduleDropReports();
    thread_ = std::thread([this] { server_.run(); });
  }

  ~Impl() {
    asio::post(server_.get_io_service(), [this] {
      std::error_code ec;
      server_.stop_listening(ec);
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& [handle, client] : clients_) server_.close(handle, websocketpp::close::status::going_away, "", ec);
      stopping_ = true;
      server_.set_timer(kCloseGraceMs, [this](const std::error_code&) { server_.stop(); });
    });
    thread_.join();
  }

  std::uint16_t port() const { return port_; }

  ChannelId advertise(Channel channel) {
    std::lock_guard<std::mutex> lock(mutex_);
    channel.id = next_channel_++;
    channels_[channel.id] = channel;
    sendToAll(advertiseJson({channel}));
    return channel.id;
  }

  void unadvertise(ChannelId id) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!channels_.erase(id)) return;
    for (auto& [handle, client] : clients_) {
      for (auto s = client.subscriptions.begin(); s != client.subscriptions.end();) {
        if (s->second != id) {
          ++s;
          continue;
        }
        client.queues.remove(s->first);
        s = client.subscriptions.erase(s);
      }
    }
    latched_.forget(id);
    sendToAll(unadvertiseJson({id}));
  }

  void publish(ChannelId channel, std::uint64_t time_ns, Payload payload, std::size_t keep) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (keep > 0 && channels_.count(channel)) latched_.keep(channel, time_ns, payload, keep);
      for (auto& [handle, client] : clients_) {
        for (const auto& [subscription, subscribed_channel] : client.subscriptions) {
          if (subscribed_channel == channel) client.queues.push({subscription, time_ns, payload}, client.socket_bytes);
        }
      }
    }
    // Drained on the server's thread; one wake-up at a time however fast messages come.
    if (!pump_posted_.exchange(true)) {
      asio::post(server_.get_io_service(), [this] {
        pump_posted_ = false;
        pump();
      });
    }
  }

  void forgetLatched(ChannelId channel) {
    std::lock_guard<std::mutex> lock(mutex_);
    latched_.forget(channel);
  }

  void broadcastTime(std::uint64_t time_ns) {
    auto frame = std::make_shared<const std::vector<std::uint8_t>>(timeFrame(time_ns));
    asio::post(server_.get_io_service(), [this, frame] {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& [handle, client] : clients_) {
        if (socketTakes(handle, frame->size())) send(handle, *frame);
      }
    });
  }

  std::set<ChannelId> subscribedChannels() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::set<ChannelId> subscribed;
    for (const auto& [handle, client] : clients_) {
      for (const auto& [subscription, channel] : client.subscriptions) subscribed.insert(channel);
    }
    return subscribed;
  }

  ServerStatistics statistics() const {
    std::lock_guard<std::mutex> lock(mutex_);
    ServerStatistics s = statistics_;
    for (const auto& [handle, client] : clients_) s.frames_dropped += client.queues.totalDrops();
    s.clients = std::count_if(clients_.begin(), clients_.end(), [](const auto& c) { return !c.second.closing; });
    return s;
  }

 private:
  void listen() {
    // One parser for the server and for the launcher's check before a run (libs/listen_address).
    const std::optional<net::ListenAddress> parsed = net::parseListenAddress(options_.address);
    if (!parsed) {
      throw std::runtime_error("cannot serve on " + net::hostAndPort(options_.address, options_.port) + ": " +
                               net::listenAddressError(options_.address));
    }
    const std::string where = net::hostAndPort(*parsed, options_.port);
    std::error_code ec;
    const asio::ip::address address = asio::ip::make_address(parsed->numeric, ec);
    if (ec) throw std::runtime_error("cannot serve on " + where + ": " + net::listenAddressError(options_.address));
    server_.listen(asio::ip::tcp::endpoint(address, options_.port), ec);
    if (ec) throw std::runtime_error("cannot serve on " + where + ": " + ec.message());
    port_ = server_.get_local_endpoint(ec).port();
  }

  // Only clients that speak the protocol: the handshake must offer foxglove.websocket.v1.
  bool validate(Handle handle) {
    WsServer::connection_ptr connection = server_.get_con_from_hdl(handle);
    for (const std::string& offered : connection->get_requested_subprotocols()) {
      if (offered == kSubprotocol) {
        connection->select_subprotocol(kSubprotocol);
        return true;
      }
    }
    connection->set_status(websocketpp::http::status_code::bad_request);
    connection->set_body(std::string("this server speaks the WebSocket subprotocol ") + kSubprotocol + " only\n");
    return false;
  }

  void onOpen(Handle handle) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_) return;
    if (clients_.size() >= options_.max_clients) {
      // Not one of the clients: what it costs ends with its close.
      send(handle,
           statusJson(StatusLevel::kError, "this viewer serves at most " + std::to_string(options_.max_clients) +
                                               " clients at once (uampc view --max-clients); try again "
                                               "when one has left"));
      std::error_code ec;
      server_.close(handle, websocketpp::close::status::try_again_later, "too many clients", ec);
      ++statistics_.clients_refused;
      return;
    }
    clients_.emplace(handle, Client(options_.queue_depth, options_.max_client_queued_bytes));
    send(handle, serverInfoJson(options_.name, session_id_));
    std::vector<Channel> all;
    for (const auto& [id, channel] : channels_) all.push_back(channel);
    send(handle, advertiseJson(all));  // the protocol wants one even when it is empty
  }

  void onGone(Handle handle) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto client = clients_.find(handle);
    if (client == clients_.end()) return;
    statistics_.frames_dropped += client->second.queues.totalDrops();  // kept past the client
    clients_.erase(client);
  }

  void onMessage(Handle handle, const WsServer::message_ptr& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto client = clients_.find(handle);
    if (client == clients_.end() || client->second.closing) return;
    if (message->get_opcode() != websocketpp::frame::opcode::text) {
      refuse(handle, client->second, "binary messages are not served (no client publishing)");
      return;
    }
    const ClientRequest request = parseClientRequest(message->get_payload());
    if (const auto* subscribe = std::get_if<SubscribeRequest>(&request)) {
      if (client->second.subscriptions.size() + subscribe->subscriptions.size() >
          options_.max_subscriptions_per_client) {
        disconnectOverBound(
            handle, client->second,
            "subscribe: " + std::to_string(subscribe->subscriptions.size()) + " subscriptions asked for beside the " +
                std::to_string(client->second.subscriptions.size()) + " this client has; a client may have at most " +
                std::to_string(options_.max_subscriptions_per_client) + " (uampc view --max-subscriptions-per-client)");
        return;
      }
      for (const Subscription& s : subscribe->subscriptions) addSubscription(handle, client->second, s);
    } else if (const auto* unsubscribe = std::get_if<UnsubscribeRequest>(&request)) {
      for (SubscriptionId id : unsubscribe->subscriptions) {
        if (!client->second.subscriptions.erase(id)) {
          refuse(handle, client->second, "unsubscribe: no subscription " + std::to_string(id));
        }
        client->second.queues.remove(id);
      }
    } else {
      refuse(handle, client->second, std::get<BadRequest>(request).message);
    }
  }

  void addSubscription(Handle handle, Client& client, const Subscription& s) {
    if (client.closing) return;
    if (!channels_.count(s.channel)) {
      refuse(handle, client, "subscribe: no channel " + std::to_string(s.channel));
    } else if (client.subscriptions.count(s.id)) {
      refuse(handle, client, "subscribe: subscription id " + std::to_string(s.id) + " is in use");
    } else {
      // A latched channel's subscription starts with its kept messages, all of them, within the
      // client's byte bound.
      const auto& kept = latched_.of(s.channel);
      client.subscriptions[s.id] = s.channel;
      client.queues.add(s.id, kept.size());
      client.socket_bytes = bufferedBytes(handle);
      for (const KeptMessage& m : kept) client.queues.push({s.id, m.time_ns, m.payload}, client.socket_bytes);
    }
  }

  // A client over one of the bounds on what clients cost: told why, then disconnected, its
  // queues freed at once.
  void disconnectOverBound(Handle handle, Client& client, const std::string& why) {
    send(handle, statusJson(StatusLevel::kError, why));
    std::error_code ec;
    server_.close(handle, websocketpp::close::status::policy_violation, "over a bound of this viewer", ec);
    ++statistics_.clients_refused;
    stopServing(client);
  }

  void stopServing(Client& client) {
    client.closing = true;
    for (const auto& [subscription, channel] : client.subscriptions) client.queues.remove(subscription);
    client.subscriptions.clear();
  }

  // A status error for a bad request; a client that keeps sending them is disconnected.
  void refuse(Handle handle, Client& client, const std::string& why) {
    if (client.closing) return;
    if (++client.bad_requests > options_.bad_requests_before_disconnect) {
      std::error_code ec;
      server_.close(handle, websocketpp::close::status::policy_violation, "too many bad requests", ec);
      ++statistics_.clients_disconnected_for_bad_requests;
      stopServing(client);
      return;
    }
    send(handle, statusJson(StatusLevel::kError, why));
  }

  // What the client's socket holds not yet written; 0 for a connection that is gone. On the
  // server's thread only: websocketpp counts them there, unguarded.
  std::size_t bufferedBytes(Handle handle) {
    std::error_code ec;
    WsServer::connection_ptr connection = server_.get_con_from_hdl(handle, ec);
    return ec ? 0 : connection->get_buffered_amount();
  }

  // Whether the client's socket takes `bytes` more now: while it holds less than
  // max_buffered_bytes with them, or anything when it is empty (a message larger than that).
  bool socketTakes(Handle handle, std::size_t bytes) {
    std::error_code ec;
    WsServer::connection_ptr connection = server_.get_con_from_hdl(handle, ec);
    if (ec) return false;
    const std::size_t buffered = connection->get_buffered_amount();
    return buffered == 0 || buffered + bytes <= options_.max_buffered_bytes;
  }

  void send(Handle handle, const std::string& text) {
    std::error_code ec;
    server_.send(handle, text, websocketpp::frame::opcode::text, ec);
  }
  void send(Handle handle, const std::vector<std::uint8_t>& frame) {
    std::error_code ec;
    server_.send(handle, frame.data(), frame.size(), websocketpp::frame::opcode::binary, ec);
    if (!ec) ++statistics_.frames_sent;
  }
  // Header and shared payload straight into the socket's one copy of the frame, which websocketpp
  // frees once it is written.
  void send(Handle handle, const QueuedMessage& message) {
    std::error_code ec;
    WsServer::connection_ptr connection = server_.get_con_from_hdl(handle, ec);
    if (ec) return;
    const auto header = messageDataHeader(message.subscription, message.time_ns);
    WsServer::message_ptr frame = connection->get_message(websocketpp::frame::opcode::binary, message.frameBytes());
    frame->append_payload(header.data(), header.size());
    frame->append_payload(message.payload->data(), message.payload->size());
    if (!connection->send(frame)) ++statistics_.frames_sent;
  }
  void sendToAll(const std::string& text) {
    for (auto& [handle, client] : clients_) send(handle, text);
  }

  // Hands each client what its socket has room for.
  void pump() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [bound_handle, client] : clients_) {
      // C++17 lambdas cannot capture a structured binding: capture a copy.
      const Handle handle = bound_handle;
      while (!client.closing) {
        const std::optional<QueuedMessage> message =
            client.queues.pop([&](std::size_t bytes) { return socketTakes(handle, bytes); });
        if (!message) break;
        send(handle, *message);
      }
      client.socket_bytes = bufferedBytes(handle);
    }
  }

  void schedulePump() {
    server_.set_timer(kPumpPeriodMs, [this](const std::error_code& ec) {
      if (ec || stopping_) return;
      pump();
      schedulePump();
    });
  }

  // Tells each lagging client what it lost, by topic.
  void scheduleDropReports() {
    server_.set_timer(kDropReportPeriodMs, [this](const std::error_code& ec) {
      if (ec || stopping_) return;
      reportDrops();
      scheduleDropReports();
    });
  }

  void reportDrops() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [handle, client] : clients_) {
      // Only into a socket with room: the counts wait for it meanwhile, so that the warnings of a
      // client that does not read never pile up.
      constexpr std::size_t kWarningBytes = 200;
      if (client.closing || !socketTakes(handle, kWarningBytes * client.subscriptions.size())) continue;
      for (const auto& [subscription, dropped] : client.queues.takeNewDrops()) {
        const auto channel = channels_.find(client.subscriptions[subscription]);
        const std::string topic = channel == channels_.end() ? "a withdrawn channel" : channel->second.topic;
        send(handle, statusJson(StatusLevel::kWarning, "dropped " + std::to_string(dropped) + " message(s) of " +
                                                           topic + ": this client reads slower than the run writes"));
      }
    }
  }

  const ServerOptions options_;
  const std::string session_id_ =
      std::to_string(std::chrono::system_clock::now().time_since_epoch() / std::chrono::milliseconds(1));
  WsServer server_;
  std::thread thread_;
  std::uint16_t port_ = 0;
  std::atomic<bool> pump_posted_{false};
  bool stopping_ = false;  // on the server's thread only

  mutable std::mutex mutex_;  // everything below
  std::map<ChannelId, Channel> channels_;
  LatchedMessages latched_;
  ChannelId next_channel_ = 1;
  std::map<Handle, Client, std::owner_less<Handle>> clients_;
  ServerStatistics statistics_;
};

Server::Server(const ServerOptions& options) : impl_(std::make_unique<Impl>(options)) {}
Server::~Server() = default;
std::uint16_t Server::port() const { return impl_->port(); }
ChannelId Server::advertise(Channel channel) { return impl_->advertise(std::move(channel)); }
void Server::unadvertise(ChannelId id) { impl_->unadvertise(id); }
void Server::publish(ChannelId channel, std::uint64_t time_ns, Payload payload) {
  impl_->publish(channel, time_ns, std::move(payload), 0);
}
void Server::publishLatched(ChannelId channel, std::uint64_t time_ns, Payload payload, std::size_t keep) {
  impl_->publish(channel, time_ns, std::move(payload), keep);
}
void Server::forgetLatched(ChannelId channel) { impl_->forgetLatched(channel); }
void Server::broadcastTime(std::uint64_t time_ns) { impl_->broadcastTime(time_ns); }
std::set<ChannelId> Server::subscribedChannels() const { return impl_->subscribedChannels(); }
ServerStatistics Server::statistics() const { return impl_->statistics(); }

}  // namespace uampc::foxglove
