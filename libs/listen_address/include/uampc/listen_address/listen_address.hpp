// The IP address a server of uampc listens on (`uampc view --address`, `--view-address` of launch
// and play), read by one parser for the viewer and for the check the launcher makes before a run
// starts: an address one accepts and the other refuses made runs start without their viewer
// (docs/decisions/one-listen-address-parser.md). Written as users write URLs: IPv6 in brackets.
#pragma once

#include <optional>
#include <string>

namespace uampc::net {

struct ListenAddress {
  std::string numeric;  // the address in its canonical form: "127.0.0.1", "::1"
  bool ipv6 = false;
  bool loopback = false;  // 127.0.0.0/8, ::1, or an IPv4-mapped 127.x address: this machine only
};

// "localhost" (127.0.0.1), an IPv4 address as four decimal numbers, or an IPv6 address, as
// inet_pton reads them; nullopt for anything else: host names, and the shorthand forms the C
// resolver also takes (127.1, 0, 0x7f000001), which asio and most tools refuse.
std::optional<ListenAddress> parseListenAddress(const std::string& text);

// Why `text` is refused, for a message that quotes it.
std::string listenAddressError(const std::string& text);

// "127.0.0.1:8765", "[::1]:8765": an address and a port as a URL holds them.
std::string hostAndPort(const ListenAddress& address, int port);
// A text that may not be an address, for messages about it: bracketed only if it is IPv6.
std::string hostAndPort(const std::string& text, int port);
// "ws://127.0.0.1:8765", "ws://[::1]:8765".
std::string webSocketUrl(const ListenAddress& address, int port);

}  // namespace uampc::net
