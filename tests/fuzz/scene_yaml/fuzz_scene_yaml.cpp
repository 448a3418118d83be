// Scene files as `uampc launch` and `uampc validate` read them: loadScene() with its whole
// validation (extends, clock, rig, components, parameters, topics), against the component types
// built beside this fuzzer (build-fuzz/lib/uampc/components: map_provider, motor_bridge,
// constant_speed_controller, lo, evaluator, tf_broadcaster). Any SceneError is a correct answer;
// a crash, hang, leak or other exception type is a finding.
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_input_file.hpp"
#include "uampc/runtime/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static uampc::ComponentCatalog catalog;  // the libraries stay loaded between inputs
  const std::string path = uampc::fuzz::writeInputFile(data, size, "scene.yaml");
  try {
    uampc::loadScene(path, {}, catalog);
  } catch (const uampc::SceneError&) {
  }
  return 0;
}
