// motor_bridge: the only component that touches the motor (docs/dev/architecture.md section 2).
// Subscribes speed commands, drives the motor, publishes encoder states as sensor_msgs/JointState
// (position = encoder angle theta, multi-turn; velocity = omega), and falls back to a safe speed
// when commands stop arriving. Backends: "sim", the simulated motor of uampc_motor_core, and
// "dynamixel", an X-series servo on a serial bus (docs/user/rig.md).
#include <cmath>
#include <memory>

#include "dynamixel_backend.hpp"
#include "sim_backend.hpp"
#include "uampc/dynamixel/control_table.hpp"
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
                                              "encoder state: position = theta (rad, multi-turn), velocity = omega")
        .soleWriter();
    spec.param("backend", "sim", "motor backend: 'sim' simulates the motor; 'dynamixel' drives an X-series servo")
        .oneOf({"sim", "dynamixel"});
    spec.param("joint_name", "motor", "name of the joint in the published JointState");
    spec.param("encoder_rate", 200.0, "encoder state publication rate, Hz").between(1.0, 10000.0);
    motor::MotorLimits defaults;
    ParameterBinding binding(spec);
    bindParameters(binding, defaults);
    spec.param("command_timeout", 0.5, "after this long without a command, drive at safe_speed, s")
        .between(0.0, 3600.0);
    spec.param("safe_speed", 0.0, "speed when commands stop arriving, rad/s").between(-1000.0, 1000.0);
    // Bounded: 1e308 overflowed to an infinite angle on the first encoder step.
    spec.param("initial_angle", 0.0, "sim: encoder angle at start, rad").between(-1.0e4, 1.0e4);
    describeDynamixel(spec);
  }

  explicit MotorBridge(Context& ctx)
      : ctx_(ctx),
        backend_(makeBackend(ctx)),
        joint_name_(ctx.paramString("joint_name")),
        command_timeout_(Time::fromSeconds(ctx.paramDouble("command_timeout"))),
        safe_speed_(ctx.paramDouble("safe_speed")),
        max_speed_(ctx.paramDouble("max_speed")),
        state_(ctx.publisher<sensor_msgs::msg::JointState>("state")),
        last_command_(ctx.now()) {
    ctx.subscribe<msg::MotorCommand>("command", [this](const msg::MotorCommand& m) { onCommand(m); });
    ctx.timer(1.0 / ctx.paramDouble("encoder_rate"), [this] { publishState(); });
  }

 private:
  // The parameters that set the simulated motor's limits: declared from its defaults, read into them.
  // max_speed also bounds the commands given to a real motor.
  static void bindParameters(ParameterBinding& b, motor::MotorLimits& limits) {
    b.bind("encoder_resolution", limits.encoder_resolution, "sim: encoder resolution, rad per count (0: exact)")
        .between(0.0, 1.0);
    b.bind("max_speed", limits.max_speed, "speed limit, rad/s; commands beyond it are clamped").between(0.0, 1000.0);
    b.bind("max_acceleration", limits.max_acceleration, "sim: acceleration limit, rad/s^2").between(1e-3, 1e9);
    b.bind("time_constant", limits.time_constant, "sim: first-order lag of the speed, s (0: none)").between(0.0, 10.0);
  }

  static void describeDynamixel(ComponentSpec& spec) {
    spec.param("port", "/dev/ttyUSB0",
               "dynamixel: serial port of the bus (a tty or a symlink such as /dev/serial/by-id/...)");
    spec.param("baud_rate", 1000000, "dynamixel: baud rate of the bus (the servo's Baud Rate, address 8)")
        .between(9600, 4000000);
    spec.param("id", 1, "dynamixel: the servo's ID").between(0, dynamixel::kMaxId);
    std::vector<std::string> models;
    for (const auto& m : dynamixel::knownModels()) models.push_back(m.name);
    spec.param("model", "XM430-W350", "dynamixel: servo model, checked against the model number it reports")
        .oneOf(models);
    spec.param("reply_timeout", 0.01, "dynamixel: wait for each status packet, s").between(0.001, 1.0);
    spec.param("max_retries", 2, "dynamixel: further tries of a request after a timeout or corrupt reply")
        .between(0, 10);
    // 0.5 s: long enough that a busy host's scheduling does not trip it (0.1 s did, on two loaded
    // cores), short enough that a rotor left running by a dead host stops within half a turn or so.
    spec.param("bus_watchdog", 0.5, "dynamixel: the servo stops itself after the bus is silent this long, s (0: off)")
        .between(0.0, 2.54);
    spec.param("reconnect_interval", 0.5, "dynamixel: after the bus is lost, try to reopen it this often, s")
        .between(0.01, 60.0);
    spec.param("on_fault", "safe_speed",
               "dynamixel: speed after the bus comes back, until the next command: 'safe_speed' or 'stop'")
        .oneOf({"safe_speed", "stop"});
  }

  static motor::MotorLimits limitsFrom(const Context& ctx) {
    motor::MotorLimits limits;
    ParameterBinding binding(ctx);
    bindParameters(binding, limits);
    return limits;
  }

  static std::unique_ptr<MotorBackend> makeBackend(const Context& ctx) {
    if (ctx.paramString("backend") == "sim")
      return std::make_unique<SimBackend>(limitsFrom(ctx), ctx.paramDouble("initial_angle"), ctx.now());
    // A real motor turns in wall time; simulated time would run it at the wrong speed.
    if (ctx.lockstep())
      throw std::runtime_error("backend 'dynamixel' drives a real motor and needs clock.mode: realtime");
    DynamixelBackendOptions o;
    o.servo.port = ctx.paramString("port");
    o.servo.baud_rate = static_cast<int>(ctx.paramInt("baud_rate"));  // SerialPort names the port if unsupported
    o.servo.id = static_cast<std::uint8_t>(ctx.paramInt("id"));
    o.servo.model = ctx.paramString("model");
    o.servo.reply_timeout_s = ctx.paramDouble("reply_timeout");
    o.servo.max_retries = static_cast<int>(ctx.paramInt("max_retries"));
    o.servo.bus_watchdog_s = ctx.paramDouble("bus_watchdog");
    o.reconnect_interval_s = ctx.paramDouble("reconnect_interval");
    o.fault_speed = ctx.paramString("on_fault") == "stop" ? 0.0 : ctx.paramDouble("safe_speed");
    return std::make_unique<DynamixelBackend>(o, ctx.log());
  }

  void onCommand(const msg::MotorCommand& m) {
    if (!std::isfinite(m.velocity())) {
      ++rejected_;
      ctx_.log().warn("ignoring a non-finite speed command on ", ctx_.topicOf("command"), " (", rejected_, " so far)");
      return;
    }
    if (std::abs(m.velocity()) > max_speed_) {
      clamp_log_.warn(ctx_.log(), "command ", m.velocity(), " rad/s exceeds max_speed ", max_speed_,
                      " rad/s; clamping (said once)");
    }
    backend_->command(std::clamp(m.velocity(), -max_speed_, max_speed_), ctx_.now());
    last_command_ = ctx_.now();
    if (in_fallback_) {
      ctx_.log().info("commands resumed; following them again");
      in_fallback_ = false;
    }
  }

  void publishState() {
    if (!in_fallback_ && ctx_.now() - last_command_ > command_timeout_) {
      ctx_.log().warn("no command on ", ctx_.topicOf("command"), " for ", (ctx_.now() - last_command_).seconds(),
                      " s; falling back to the safe speed ", safe_speed_, " rad/s");
      in_fallback_ = true;
      backend_->command(safe_speed_, ctx_.now());
    }
    const std::optional<MotorReading> reading = backend_->read(ctx_.now());
    if (!reading) return;
    sensor_msgs::msg::JointState state;
    state.header().stamp(toMsg(reading->stamp));
    // The encoder measures the rotor against the motor's fixed part (TF: motor -> rotor).
    state.header().frame_id("motor");
    state.name({joint_name_});
    state.position({reading->position});
    state.velocity({reading->velocity});
    state_.publish(state);
  }

  Context& ctx_;
  std::unique_ptr<MotorBackend> backend_;
  std::string joint_name_;
  Time command_timeout_;
  double safe_speed_;
  double max_speed_;
  Publisher<sensor_msgs::msg::JointState> state_;
  Time last_command_;
  bool in_fallback_ = false;
  RateLimitedLog clamp_log_ = RateLimitedLog::once();
  long rejected_ = 0;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::MotorBridge, "motor_bridge")
