// The components of one process group (process_group.cpp), each with its ContextImpl.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "uampc/runtime/component.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/scene.hpp"
#include "context_impl.hpp"

namespace uampc::process {

struct ProcessState;

// The components of one process: constructed in the scene's order, each with its context, and at
// the end each shut down, even after another has failed.
class ComponentGroup {
 public:
  // serialized_dds: the participant of the process's serialized ports, made on first use.
  ComponentGroup(const Scene& scene, const std::string& process, const std::string& output_directory, DdsNode& dds,
                 std::function<DdsNode&()> serialized_dds, ProcessState& state, const Logger& log);

  // False (said in the log) when a component could not start or left a declared port unopened.
  bool create();

  // Every component's shutdown, even after one has failed: each writes its own outputs (a
  // recorder's file is whole only once it is closed), and one component's full disk is no reason
  // to lose another's files. False when any failed.
  bool shutDown();

  // The components themselves, before the readers and writers their callbacks use.
  void destroy() { components_.clear(); }

 private:
  bool construct(const ComponentInstance& instance);

  bool hasSerializedPorts() const;

  const Scene& scene_;
  const std::string& process_;
  const std::string& output_directory_;
  DdsNode& dds_;
  std::function<DdsNode&()> serialized_dds_;
  ProcessState& state_;
  const Logger& log_;
  std::vector<std::unique_ptr<ContextImpl>> contexts_;
  std::vector<std::pair<std::string, std::unique_ptr<Component>>> components_;
};

}  // namespace uampc::process
