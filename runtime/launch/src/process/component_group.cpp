#include "component_group.hpp"

#include <exception>

namespace uampc::process {

ComponentGroup::ComponentGroup(const Scene& scene, const std::string& process, const std::string& output_directory,
                               DdsNode& dds, std::function<DdsNode&()> serialized_dds, ProcessState& state,
                               const Logger& log)
    : scene_(scene),
      process_(process),
      output_directory_(output_directory),
      dds_(dds),
      serialized_dds_(std::move(serialized_dds)),
      state_(state),
      log_(log) {}

bool ComponentGroup::create() {
  // The participant of serialized ports (a recorder's) is made before any component, beside the
  // process's main participant, so that the two announce themselves to each other at the same
  // time. Made on first use, in the middle of the components' constructors, it missed the main
  // participant about every second run of config/scenes/record_default.yaml on one core, and the
  // start then waited for Fast DDS's next periodic announcement, 3 s later
  // (docs/results/recording-cost.md).
  if (hasSerializedPorts()) serialized_dds_();
  for (const auto& instance : scene_.components) {
    if (instance.process != process_) continue;
    if (!construct(instance)) return false;
  }
  return true;
}

bool ComponentGroup::shutDown() {
  bool ok = true;
  for (auto& [name, component] : components_) {
    try {
      component->shutdown();
    } catch (const std::exception& e) {
      log_.error("component '", name, "' failed while shutting down: ", e.what());
      ok = false;
    }
  }
  return ok;
}

bool ComponentGroup::construct(const ComponentInstance& instance) {
  contexts_.push_back(
      std::make_unique<ContextImpl>(scene_, instance, output_directory_, dds_, serialized_dds_, state_));
  try {
    components_.emplace_back(instance.name, instance.library->create(*contexts_.back()));
  } catch (const std::exception& e) {
    log_.error("component '", instance.name, "' (", instance.type, ") could not start: ", e.what());
    return false;
  }
  for (const std::string& port : contexts_.back()->unopenedPorts()) {
    log_.error("component '", instance.name, "' (", instance.type, ") declares port '", port,
               "' but did not open it in its constructor: every declared port must get a publisher or a "
               "subscription (ignore the samples if they are not needed), or the run waits for it forever");
    return false;
  }
  return true;
}

bool ComponentGroup::hasSerializedPorts() const {
  for (const auto& instance : scene_.components) {
    if (instance.process != process_) continue;
    for (const PortSpec& port : instance.ports)
      if (port.serialized) return true;
  }
  return false;
}

}  // namespace uampc::process
