// `--set NAME=VALUE` as `uampc launch|validate|graph` reads it: each line of the input is one
// --set text, parsed by parseOverride() and applied by loadScene() to tests/fuzz/set_override/
// scene.yaml (one component of each type built beside this fuzzer, a clock and a rig), exactly
// as the command line does. Any SceneError is a correct answer.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "uampc/runtime/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static uampc::ComponentCatalog catalog;
  static const std::string scene = UAMPC_FUZZ_SOURCE_DIR "/set_override/scene.yaml";
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<uampc::Override> overrides;
  try {
    for (std::string text; std::getline(lines, text);) overrides.push_back(uampc::parseOverride(text));
    uampc::loadScene(scene, overrides, catalog);
  } catch (const uampc::SceneError&) {
  }
  return 0;
}
