// Test component: publishes uampc_test_msgs/msg/Ping, a type from an IDL package of its own
// (tests/idl), for the test that a component library registers its own types when it is loaded.
#include <cstdint>

#include "uampc/msgs/uampc_test_msgs.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class PingPublisher : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: publishes Ping, a message type the runtime was not built with";
    spec.output<uampc_test_msgs::msg::Ping>("ping", "/ping", QosPreset::kControl, "a counter");
  }

  explicit PingPublisher(Context& ctx) : ping_(ctx.publisher<uampc_test_msgs::msg::Ping>("ping")) {
    ctx.timer(0.1, [this] { publish(); });
  }

 private:
  void publish() {
    uampc_test_msgs::msg::Ping ping;
    ping.count(count_++);
    ping.text("ping");
    ping_.publish(ping);
  }

  Publisher<uampc_test_msgs::msg::Ping> ping_;
  std::uint64_t count_ = 0;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::PingPublisher, "ping_publisher")
