#include "uampc/listen_address/listen_address.hpp"

#include <gtest/gtest.h>

namespace uampc::net {
namespace {

TEST(ListenAddress, ReadsWhatTheViewerCanBind) {
  const auto v4 = parseListenAddress("127.0.0.1");
  ASSERT_TRUE(v4);
  EXPECT_EQ(v4->numeric, "127.0.0.1");
  EXPECT_FALSE(v4->ipv6);
  EXPECT_TRUE(v4->loopback);
  EXPECT_EQ(parseListenAddress("localhost")->numeric, "127.0.0.1");
  EXPECT_FALSE(parseListenAddress("0.0.0.0")->loopback);
  EXPECT_FALSE(parseListenAddress("192.168.1.20")->loopback);
  const auto v6 = parseListenAddress("0:0:0:0:0:0:0:1");
  ASSERT_TRUE(v6);
  EXPECT_EQ(v6->numeric, "::1");
  EXPECT_TRUE(v6->ipv6);
  EXPECT_TRUE(v6->loopback);
  EXPECT_FALSE(parseListenAddress("::")->loopback);
  EXPECT_TRUE(parseListenAddress("::ffff:127.0.0.1")->loopback);
}

// What the C resolver reads as IPv4 but the viewer's socket library refuses: refused here, so that
// `launch --view` refuses it before a run starts.
TEST(ListenAddress, RefusesShorthandsAndNames) {
  for (const char* text : {"127.1", "0", "0x7f000001", "017700000001", "127.0.0.1.", "", "somewhere", "[::1]", "::1%lo",
                           " 127.0.0.1", "256.0.0.1"}) {
    EXPECT_FALSE(parseListenAddress(text)) << text;
  }
  EXPECT_NE(listenAddressError("127.1").find("'127.1' is not an IP address"), std::string::npos);
}

TEST(ListenAddress, IPv6IsBracketedInUrls) {
  EXPECT_EQ(webSocketUrl(*parseListenAddress("::1"), 8765), "ws://[::1]:8765");
  EXPECT_EQ(webSocketUrl(*parseListenAddress("127.0.0.1"), 8765), "ws://127.0.0.1:8765");
  EXPECT_EQ(hostAndPort(std::string("::1"), 80), "[::1]:80");
  EXPECT_EQ(hostAndPort(std::string("127.1"), 80), "127.1:80");
}

}  // namespace
}  // namespace uampc::net
