// constant_speed_controller: the paper's baseline. Commands one speed, always: 3.6 rad/s by
// default (the paper's constant-speed baseline); speed 0 is the zero-speed baseline. With `speeds`
// it steps through a list instead, each for `speed_period`: a rig calibration needs a speed that
// varies to see the LiDAR-to-encoder clock offset (docs/user/calibration.md).
#include <cmath>
#include <vector>

#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class ConstantSpeedController : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Commands a constant motor speed (the paper's baseline; 0 gives zero speed)";
    spec.output<msg::MotorCommand>("command", "/motor/command", QosPreset::kControl, "speed command, rad/s")
        .soleWriter();
    spec.param("speed", 3.6, "commanded speed, rad/s").between(-1000.0, 1000.0);
    spec.param("speeds", std::vector<double>{},
               "speeds stepped through in turn, each for speed_period, rad/s (empty: speed, always)")
        .between(-1000.0, 1000.0);
    spec.param("speed_period", 1.0, "how long each of speeds is commanded, s").between(0.01, 3600.0);
    spec.param("rate", 10.0, "command rate, Hz (the motor bridge falls back if commands stop)")
        .between(0.01, 10000.0);
  }

  explicit ConstantSpeedController(Context& ctx)
      : ctx_(ctx),
        speed_(ctx.paramDouble("speed")),
        speeds_(ctx.paramDoubleList("speeds")),
        speed_period_(ctx.paramDouble("speed_period")),
        command_(ctx.publisher<msg::MotorCommand>("command")) {
    ctx.timer(1.0 / ctx.paramDouble("rate"), [this] { publish(); });
  }

 private:
  void publish() {
    msg::MotorCommand command;
    command.header().stamp(toMsg(ctx_.now()));
    command.header().frame_id("motor");  // the rotor's speed about the motor frame's z axis
    command.velocity(speedAt(ctx_.now().seconds()));
    command_.publish(command);
  }

  double speedAt(double t) const {
    if (speeds_.empty()) return speed_;
    const auto step = static_cast<long long>(std::floor(t / speed_period_));
    const auto n = static_cast<long long>(speeds_.size());
    return speeds_[static_cast<std::size_t>(((step % n) + n) % n)];
  }

  Context& ctx_;
  double speed_;
  std::vector<double> speeds_;
  double speed_period_;
  Publisher<msg::MotorCommand> command_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::ConstantSpeedController, "constant_speed_controller")
