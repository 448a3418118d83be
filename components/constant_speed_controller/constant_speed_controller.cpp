// constant_speed_controller: the paper's baseline. Commands one speed, always: 3.6 rad/s by
// default (the paper's constant-speed baseline); speed 0 is the zero-speed baseline.
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
    spec.param("rate", 10.0, "command rate, Hz (the motor bridge falls back if commands stop)")
        .between(0.01, 10000.0);
  }

  explicit ConstantSpeedController(Context& ctx)
      : ctx_(ctx), speed_(ctx.paramDouble("speed")), command_(ctx.publisher<msg::MotorCommand>("command")) {
    ctx.timer(1.0 / ctx.paramDouble("rate"), [this] { publish(); });
  }

 private:
  void publish() {
    msg::MotorCommand command;
    command.header().stamp(toMsg(ctx_.now()));
    command.header().frame_id("motor");  // the rotor's speed about the motor frame's z axis
    command.velocity(speed_);
    command_.publish(command);
  }

  Context& ctx_;
  double speed_;
  Publisher<msg::MotorCommand> command_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::ConstantSpeedController, "constant_speed_controller")
