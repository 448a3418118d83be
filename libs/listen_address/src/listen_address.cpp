#include "uampc/listen_address/listen_address.hpp"

#include <arpa/inet.h>

#include <cstring>

namespace uampc::net {

std::optional<ListenAddress> parseListenAddress(const std::string& text) {
  const std::string host = text == "localhost" ? "127.0.0.1" : text;
  char canonical[INET6_ADDRSTRLEN] = {};
  ListenAddress address;
  in_addr v4{};
  in6_addr v6{};
  // inet_pton, not inet_aton or getaddrinfo: those read "127.1" and "0x7f000001" too.
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) {
    inet_ntop(AF_INET, &v4, canonical, sizeof canonical);
    address.loopback = (ntohl(v4.s_addr) >> 24) == 127;
  } else if (inet_pton(AF_INET6, host.c_str(), &v6) == 1) {
    inet_ntop(AF_INET6, &v6, canonical, sizeof canonical);
    address.ipv6 = true;
    address.loopback = IN6_IS_ADDR_LOOPBACK(&v6) || (IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127);
  } else {
    return std::nullopt;
  }
  address.numeric = canonical;
  return address;
}

std::string listenAddressError(const std::string& text) {
  return "'" + text +
         "' is not an IP address (four decimal numbers as 127.0.0.1, an IPv6 address as ::1, or localhost)";
}

std::string hostAndPort(const ListenAddress& address, int port) {
  const std::string host = address.ipv6 ? "[" + address.numeric + "]" : address.numeric;
  return host + ":" + std::to_string(port);
}

std::string hostAndPort(const std::string& text, int port) {
  // A colon is in every IPv6 address and in no IPv4 address or host name.
  const bool ipv6 = text.find(':') != std::string::npos;
  return (ipv6 ? "[" + text + "]" : text) + ":" + std::to_string(port);
}

std::string webSocketUrl(const ListenAddress& address, int port) { return "ws://" + hostAndPort(address, port); }

}  // namespace uampc::net
