// Test component: misbehaves on purpose at a given time, to test how the runtime reports it.
//   mode abort: the process dies (SIGABRT);  mode throw: a callback throws;
//   mode hang: a callback never returns (lockstep must time out, not hang);
//   mode exit: the process exits with status 3;  mode throw_at_shutdown: shutdown() throws (the
//   run itself goes well), as a component whose last write fails on a full disk.
#include <cstdlib>
#include <thread>

#include "uampc/runtime/component.hpp"

namespace uampc {

class FaultInjector : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: fails on purpose at a given time";
    spec.requiredParam("mode", ParameterType::kString, "how to fail: abort, throw, hang, exit or throw_at_shutdown")
        .oneOf({"abort", "throw", "hang", "exit", "throw_at_shutdown"});
    spec.param("at", 0.1, "when to fail, s of clock time since start").atLeast(0.0);
  }

  explicit FaultInjector(Context& ctx) : ctx_(ctx), mode_(ctx.paramString("mode")), start_(ctx.now()) {
    at_ = Time::fromSeconds(ctx.paramDouble("at"));
    ctx.timer(0.01, [this] { tick(); });
  }

  void shutdown() override {
    if (mode_ == "throw_at_shutdown") throw std::runtime_error("injected failure at shutdown");
  }

 private:
  void tick() {
    if (mode_ == "throw_at_shutdown" || ctx_.now() - start_ < at_) return;
    if (mode_ == "abort") std::abort();
    if (mode_ == "exit") std::exit(3);
    if (mode_ == "hang") std::this_thread::sleep_for(std::chrono::hours(1));
    throw std::runtime_error("injected failure");
  }

  Context& ctx_;
  std::string mode_;
  Time start_;
  Time at_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::FaultInjector, "fault_injector")
