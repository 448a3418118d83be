// Test component: records motor states and commands, as they arrive, to CSV files in the run's
// output directory (motor_states.csv, motor_commands.csv), at full double precision, so that
// tests can check theta(t) and compare runs byte for byte.
#include <cstdio>
#include <memory>

#include "uampc/runtime/component.hpp"

namespace uampc {

class MotorRecorder : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: records motor states and commands to CSV";
    spec.input<sensor_msgs::msg::JointState>("state", "/motor/state", QosPreset::kControl, "motor states");
    spec.input<msg::MotorCommand>("command", "/motor/command", QosPreset::kControl, "motor commands");
  }

  explicit MotorRecorder(Context& ctx) : ctx_(ctx) {
    if (ctx.outputDirectory().empty()) throw std::runtime_error("motor_recorder needs an output directory (--out)");
    states_ = open("motor_states.csv", "stamp,position,velocity\n");
    commands_ = open("motor_commands.csv", "received,stamp,velocity\n");
    ctx.subscribe<sensor_msgs::msg::JointState>("state", [this](const sensor_msgs::msg::JointState& m) {
      std::fprintf(states_.get(), "%.9f,%.17g,%.17g\n", fromMsg(m.header().stamp()).seconds(), m.position().at(0),
                   m.velocity().at(0));
    });
    ctx.subscribe<msg::MotorCommand>("command", [this](const msg::MotorCommand& m) {
      std::fprintf(commands_.get(), "%.9f,%.9f,%.17g\n", ctx_.now().seconds(), fromMsg(m.header().stamp()).seconds(),
                   m.velocity());
    });
  }

 private:
  using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;
  File open(const char* name, const char* header) {
    const std::string path = ctx_.outputDirectory() + "/" + ctx_.name() + "_" + name;
    File f(std::fopen(path.c_str(), "w"), &std::fclose);
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fputs(header, f.get());
    return f;
  }

  Context& ctx_;
  File states_{nullptr, &std::fclose};
  File commands_{nullptr, &std::fclose};
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::MotorRecorder, "motor_recorder")
