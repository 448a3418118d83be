// Test component: misbehaves on purpose at a given time, to test how the runtime reports it.
//   mode abort: the process dies (SIGABRT);  mode throw: a callback throws;
//   mode hang: a callback never returns (lockstep must time out, not hang);
//   mode exit: the process exits with status 3.
#include <cstdlib>
#include <thread>

#include "uampc/runtime/component.hpp"

namespace uampc {

class FaultInjector : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: fails on purpose at a given time";
    spec.requiredParam("mode", ParameterType::kString, "how to fail: abort, throw, hang or exit")
        .oneOf({"abort", "throw", "hang", "exit"});
    spec.param("at", 0.1, "when to fail, s of clock time since start").atLeast(0.0);
  }

  explicit FaultInjector(Context& ctx) : ctx_(ctx), mode_(ctx.paramString("mode")), start_(ctx.now()) {
    at_ = Time::fromSeconds(ctx.paramDouble("at"));
    ctx.timer(0.01, [this] { tick(); });
  }

 private:
  void tick() {
    if (ctx_.now() - start_ < at_) return;
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
