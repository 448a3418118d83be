// Test component: holds its process's start until a file exists, so that a test can stop a scene
// while it is starting (Ctrl-C while the processes wait for one another) without racing it.
#include <chrono>
#include <filesystem>
#include <thread>

#include "uampc/runtime/component.hpp"

namespace uampc {

class StartGate : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Test: its process starts only once a given file exists";
    spec.requiredParam("file", ParameterType::kString, "the file whose existence lets the process start");
  }

  // Waits here, in construction: the process has not said it is ready, so the others and the
  // clock wait for it. A signal does not end the wait; the test makes the file after signalling.
  explicit StartGate(Context& ctx) {
    const std::string file = ctx.paramString("file");
    while (!std::filesystem::exists(file)) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::StartGate, "start_gate")
