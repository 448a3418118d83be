// Test component: a misbehaving controller that publishes panoramas the evaluator cannot read
// (16-bit depth, or fewer bytes than width x height floats), or never opens its declared port.
#include <optional>

#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class BadPanoramaPublisher : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: publishes malformed panoramas";
    spec.output<sensor_msgs::msg::Image>("panorama", "/mpc/panorama", QosPreset::kSensor, "malformed images");
    spec.requiredParam("mode", ParameterType::kString, "wrong_encoding, short_data or never_opened")
        .oneOf({"wrong_encoding", "short_data", "never_opened"});
  }

  explicit BadPanoramaPublisher(Context& ctx)
      : ctx_(ctx), mode_(ctx.paramString("mode")) {
    if (mode_ == "never_opened") return;
    pub_.emplace(ctx.publisher<sensor_msgs::msg::Image>("panorama"));
    ctx.timer(0.1, [this] { publish(); });
  }

 private:
  void publish() {
    sensor_msgs::msg::Image image;
    image.header().stamp(toMsg(ctx_.now()));
    image.width(180);
    image.height(90);
    image.encoding(mode_ == "wrong_encoding" ? "16UC1" : "32FC1");
    image.step(mode_ == "wrong_encoding" ? 180 * 2 : 180 * 4);
    image.data().resize(mode_ == "wrong_encoding" ? 180 * 90 * 2 : 1000);
    pub_->publish(image);
  }

  Context& ctx_;
  std::string mode_;
  std::optional<Publisher<sensor_msgs::msg::Image>> pub_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::BadPanoramaPublisher, "bad_panorama_publisher")
