// motor_bridge: the only component that touches the motor (docs/design.md section 2).
// Subscribes speed commands, drives the motor, publishes encoder states as sensor_msgs/JointState
// (position = encoder angle theta, multi-turn; velocity = omega), and falls back to a safe speed
// when commands stop arriving. Backend "sim" is the simulated motor of uampc_motor_core.
#include <cmath>

#include "uampc/motor/simulated_motor.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/component.hpp"
#include "uampc/runtime/parameter_binding.hpp"

namespace uampc {

class MotorBridge : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Drives the motor from speed commands and publishes its encoder state";
    spec.input<msg::MotorCommand>("command", "/motor/command", QosPreset::kControl, "speed commands, rad/s");
    spec.output<sensor_msgs::msg::JointState>("state", "/motor/state", QosPreset::kControl,
                                              "encoder state: position = theta (rad, multi-turn), velocity = omega");
    spec.param("backend", "sim", "motor backend; 'sim' simulates the motor").oneOf({"sim"});
    spec.param("joint_name", "motor", "name of the joint in the published JointState");
    spec.param("encoder_rate", 200.0, "encoder state publication rate, Hz").between(1.0, 10000.0);
    motor::MotorLimits defaults;
    ParameterBinding binding(spec);
    bindParameters(binding, defaults);
    spec.param("command_timeout", 0.5, "after this long without a command, drive at safe_speed, s")
        .between(0.0, 3600.0);
    spec.param("safe_speed", 0.0, "speed when commands stop arriving, rad/s").between(-1000.0, 1000.0);
    // Bounded: 1e308 overflowed to an infinite angle on the first encoder step.
    spec.param("initial_angle", 0.0, "encoder angle at start, rad").between(-1.0e4, 1.0e4);
  }

  explicit MotorBridge(Context& ctx)
      : ctx_(ctx),
        motor_(limitsFrom(ctx), ctx.paramDouble("initial_angle")),
        joint_name_(ctx.paramString("joint_name")),
        command_timeout_(Time::fromSeconds(ctx.paramDouble("command_timeout"))),
        safe_speed_(ctx.paramDouble("safe_speed")),
        max_speed_(ctx.paramDouble("max_speed")),
        state_(ctx.publisher<sensor_msgs::msg::JointState>("state")),
        last_update_(ctx.now()),
        last_command_(ctx.now()) {
    // At rest until the first command; if none comes within command_timeout, the safe speed.
    motor_.command(0.0);
    ctx.subscribe<msg::MotorCommand>("command", [this](const msg::MotorCommand& m) { onCommand(m); });
    ctx.timer(1.0 / ctx.paramDouble("encoder_rate"), [this] { publishState(); });
  }

 private:
  // The parameters that set the simulated motor's limits: declared from its defaults, read into them.
  static void bindParameters(ParameterBinding& b, motor::MotorLimits& limits) {
    b.bind("encoder_resolution", limits.encoder_resolution, "encoder resolution, rad per count (0: exact)")
        .between(0.0, 1.0);
    b.bind("max_speed", limits.max_speed, "speed limit, rad/s; commands beyond it are clamped").between(0.0, 1000.0);
    b.bind("max_acceleration", limits.max_acceleration, "acceleration limit, rad/s^2").between(1e-3, 1e9);
    b.bind("time_constant", limits.time_constant, "first-order lag of the speed, s (0: none)").between(0.0, 10.0);
  }

  static motor::MotorLimits limitsFrom(const Context& ctx) {
    motor::MotorLimits limits;
    ParameterBinding binding(ctx);
    bindParameters(binding, limits);
    return limits;
  }

  // Brings the motor to the present under the command it had so far.
  void advanceToNow() {
    const Time now = ctx_.now();
    motor_.advance((now - last_update_).seconds());
    last_update_ = now;
  }

  void onCommand(const msg::MotorCommand& m) {
    if (!std::isfinite(m.velocity())) {
      ++rejected_;
      ctx_.log().warn("ignoring a non-finite speed command on ", ctx_.topicOf("command"), " (", rejected_, " so far)");
      return;
    }
    advanceToNow();
    if (std::abs(m.velocity()) > max_speed_) {
      clamp_log_.warn(ctx_.log(), "command ", m.velocity(), " rad/s exceeds max_speed ", max_speed_,
                      " rad/s; clamping (said once)");
    }
    motor_.command(m.velocity());
    last_command_ = ctx_.now();
    if (in_fallback_) {
      ctx_.log().info("commands resumed; following them again");
      in_fallback_ = false;
    }
  }

  void publishState() {
    advanceToNow();
    if (!in_fallback_ && ctx_.now() - last_command_ > command_timeout_) {
      ctx_.log().warn("no command on ", ctx_.topicOf("command"), " for ", (ctx_.now() - last_command_).seconds(),
                      " s; falling back to the safe speed ", safe_speed_, " rad/s");
      in_fallback_ = true;
      motor_.command(safe_speed_);
    }
    sensor_msgs::msg::JointState state;
    state.header().stamp(toMsg(ctx_.now()));
    // The encoder measures the rotor against the motor's fixed part (TF: motor -> rotor).
    state.header().frame_id("motor");
    state.name({joint_name_});
    state.position({motor_.encoderTheta()});
    state.velocity({motor_.omega()});
    state_.publish(state);
  }

  Context& ctx_;
  motor::SimulatedMotor motor_;
  std::string joint_name_;
  Time command_timeout_;
  double safe_speed_;
  double max_speed_;
  Publisher<sensor_msgs::msg::JointState> state_;
  Time last_update_;
  Time last_command_;
  bool in_fallback_ = false;
  RateLimitedLog clamp_log_ = RateLimitedLog::once();
  long rejected_ = 0;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::MotorBridge, "motor_bridge")
