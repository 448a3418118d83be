// What a step of a process group hands its components (process_group.cpp): their inputs, then
// their timers.
#pragma once

#include <deque>
#include <functional>
#include <string>

#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/scene.hpp"
#include "process_state.hpp"

namespace uampc::process {

// What a step hands the components: the samples due on every input, then the timers due. Each
// call is guarded: an exception becomes the process's failure, naming the component.
class StepDelivery {
 public:
  StepDelivery(const Scene& scene, ProcessState& state, const Logger& log) : scene_(scene), state_(state), log_(log) {}

  // The inputs, then (if they went well) the timers. In lockstep, `expected` holds the samples
  // written on each topic before this step; `give_up` says whether to stop waiting for them.
  bool deliver(const TopicCounts* expected, const std::function<bool()>& give_up) {
    return deliverInputs(expected, give_up) && fireTimers();
  }

 private:
  // Calls `work` and turns an exception into a failure that names the component.
  bool guarded(const std::string& component, const char* what, const std::function<void()>& work);

  // Delivers the samples that arrived, in a fixed order: readers in the order components created
  // them, samples of one reader in arrival order. In lockstep, exactly the samples published in
  // earlier steps are delivered: the reader first waits until it holds as many samples stamped
  // before now as the processes' acknowledgements say were written on its topic (expected), and
  // samples of the current step (source time >= now) wait for the next one. Every hop between
  // components therefore takes exactly one step, in one process or in several, which is what
  // makes runs deterministic.
  bool deliverInputs(const TopicCounts* expected, const std::function<bool()>& give_up);

  // Lockstep: takes samples until the reader holds every sample written before now on its topic.
  bool awaitSamples(ReaderPort& r, std::deque<Sample>& samples, const TopicCounts& expected,
                    const std::function<bool()>& give_up);

  bool fireTimers();

  const Scene& scene_;
  ProcessState& state_;
  const Logger& log_;
};

}  // namespace uampc::process
