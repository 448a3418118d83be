// Test library: claims a component ABI version this runtime does not have. The loader must refuse
// it with a message, not load it.
#include "uampc/runtime/component.hpp"

extern "C" __attribute__((visibility("default"))) const uampc::ComponentPlugin* uampc_component_plugin() {
  static const uampc::ComponentPlugin plugin{uampc::kComponentAbiVersion + 41, "bad_abi", nullptr, nullptr};
  return &plugin;
}
