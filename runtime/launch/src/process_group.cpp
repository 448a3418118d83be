#include "uampc/runtime/process_group.hpp"

#include <chrono>
#include <exception>
#include <functional>
#include <memory>
#include <thread>
#include <utility>

#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/dds_security.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/wall_clock.hpp"
#include "lockstep_clock.hpp"
#include "process/component_group.hpp"
#include "process/lockstep_protocol.hpp"
#include "process/process_state.hpp"
#include "process/step_delivery.hpp"
#include "process/unmatched_ports.hpp"

// The parts of a process group live in process/, in namespace uampc::process (each file names
// what it holds); this file drives them.
namespace uampc {

namespace process {

using SteadyClock = std::chrono::steady_clock;

namespace {

// How one step ended for the process.
enum class StepOutcome { kDone, kStopped, kFailed };

int exitCodeOf(StepOutcome outcome) { return outcome == StepOutcome::kFailed ? 1 : 0; }

// Drives the components of one process: builds them, waits for discovery, then runs the steps in
// lockstep (following the launcher's clock, or stepping itself) or in real time.
class ProcessRunner {
 public:
  ProcessRunner(const Scene& scene, std::string process, std::string output_directory, bool own_clock)
      : scene_(scene),
        process_(std::move(process)),
        output_directory_(std::move(output_directory)),
        own_clock_(own_clock),
        dds_(scene.domain_id, scene.dds_profile, scene.clock.mode == ClockMode::kLockstep, "uampc/" + process_,
             securityIdentity(scene.security_directory, process_)),
        log_(process_, [this] { return state_.now.seconds(); }),
        components_(
            scene_, process_, output_directory_, dds_, [this]() -> DdsNode& { return serializedDds(); }, state_, log_),
        delivery_(scene_, state_, log_) {
    state_.lockstep = scene.clock.mode == ClockMode::kLockstep;
    state_.step = scene.clock.step;
    state_.now = state_.lockstep ? Time{0} : wallNow();
    state_.started = !state_.lockstep;
  }

  // Components first, then the DDS readers and writers their callbacks used, then the protocol's.
  ~ProcessRunner() {
    components_.destroy();
    for (auto& r : state_.dds_readers) r->node->deleteReader(r->reader);
    state_.writers.clear();  // each deletes its DDS writer
    protocol_.reset();
  }

  int run(const std::atomic<bool>& stop) {
    if (!components_.create()) return 1;
    const int code = state_.lockstep ? runLockstep(stop) : runRealtime(stop);
    if (code != 0 && protocol_) protocol_->deliverFailure();
    return components_.shutDown() ? code : 1;
  }

 private:
  DdsNode& serializedDds() {
    if (!serialized_dds_) {
      serialized_dds_ = std::make_unique<DdsNode>(scene_.domain_id, scene_.dds_profile, state_.lockstep,
                                                  "uampc/" + process_ + "/serialized",
                                                  securityIdentity(scene_.security_directory, process_));
    }
    return *serialized_dds_;
  }

  // Until every port and the protocol's endpoints are matched; false on timeout (said) or stop.
  bool waitForMatches(const std::atomic<bool>& stop) {
    const auto deadline = SteadyClock::now() + std::chrono::duration<double>(scene_.clock.startupTimeout());
    // A start that takes long says what it waits for (a component on another host, a process that
    // failed to start), every few seconds.
    auto next_report = SteadyClock::now() + std::chrono::seconds(2);
    for (;;) {
      const std::string missing = unmatchedPorts(scene_, state_) + protocol_->unmatched();
      if (missing.empty()) return true;
      if (stop) return false;
      if (SteadyClock::now() > deadline) {
        log_.error("DDS discovery did not complete within ", scene_.clock.startupTimeout(),
                   " s; still missing:", missing, securedStartHint(scene_));
        return false;
      }
      if (SteadyClock::now() > next_report) {
        log_.info("starting: waiting for", missing);
        next_report = SteadyClock::now() + std::chrono::seconds(5);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }

  // Waiting for samples gives up on a stop or another run on the domain.
  std::function<bool()> giveUpOn(const std::atomic<bool>& stop) {
    return [this, &stop] { return stop || protocol_->anotherRunStops(); };
  }

  int runLockstep(const std::atomic<bool>& stop) {
    protocol_ = std::make_unique<LockstepProtocol>(scene_, process_, own_clock_, dds_, state_, log_);
    if (!waitForMatches(stop)) return stop ? 0 : 1;
    state_.started = true;
    protocol_->sayReady();
    return own_clock_ ? runOwnClock(stop) : followLauncherClock(stop);
  }

  // The launcher's clock ticks each step once every process acknowledged the one before. When the
  // clock leaves, the run is over for this process (docs/dev/time-and-lockstep.md).
  int followLauncherClock(const std::atomic<bool>& stop) {
    while (!stop) {
      state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::milliseconds(100));
      if (protocol_->anotherRunStops()) return 1;
      std::vector<Time> ticks = protocol_->takeTicks();
      // Looked for only when no tick came, not at every step. A clock's last tick arrives before it
      // leaves: the ticks are taken once more after seeing it gone.
      const bool clock_left = ticks.empty() && protocol_->clockLeft();
      if (clock_left) ticks = protocol_->takeTicks();
      for (const Time t : ticks) {
        const StepOutcome outcome = tickedStep(t, stop);
        if (outcome != StepOutcome::kDone) return exitCodeOf(outcome);
      }
      if (clock_left) return afterTheClockLeft(stop);
      // Data may have arrived for later steps; the tick will come.
    }
    return 0;
  }

  // At the scene's end (clock.duration), or of a run without an end, the clock's leaving ends this
  // process: `uampc clock` finished or was stopped. Before the end it is a failure, unless the
  // process is being stopped too: under `uampc launch` the launcher stops its processes right after
  // its clock, whichever ended the run.
  int afterTheClockLeft(const std::atomic<bool>& stop) {
    const double end_s = scene_.clock.duration_s;
    const double now_s = state_.now.seconds();
    if (end_s <= 0 || now_s >= end_s - 0.5 * scene_.clock.step.seconds()) {
      log_.info("the lockstep clock ended the run");
      return 0;
    }
    const auto patience = SteadyClock::now() + std::chrono::seconds(2);
    while (!stop && SteadyClock::now() < patience) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (stop) return 0;
    state_.failure = "the lockstep clock left at " + std::to_string(now_s) + " s, before the run's end at " +
                     std::to_string(end_s) + " s (`uampc clock` stopped or failed)";
    log_.error(state_.failure);
    return 1;
  }

  // One step the launcher's clock ticked: the samples of the step before as every process counted
  // them, the timers, then this process's acknowledgement (also when a component failed: it says
  // why).
  StepOutcome tickedStep(Time t, const std::atomic<bool>& stop) {
    const std::int64_t step = t.ns / scene_.clock.step.ns;
    state_.now = t;
    TopicCounts expected;
    if (!protocol_->awaitAcks(step - 1, expected, stop)) return stop ? StepOutcome::kStopped : StepOutcome::kFailed;
    const bool ok = delivery_.deliver(&expected, giveUpOn(stop));
    if (!ok && stop) return StepOutcome::kStopped;  // stopped while waiting for samples that will not come
    protocol_->sendAck(step, t);
    return ok ? StepOutcome::kDone : StepOutcome::kFailed;
  }

  // The process steps itself (Scene::processesStepThemselves()): the same steps as with the
  // launcher's clock, and the same outputs (lockstep_test), without a tick from another process.
  // The launcher's clock only ever advanced once every process had acknowledged the step, and the
  // acknowledgements are what each process waits for anyway: with several processes each one
  // starts step k once it holds every process's acknowledgement of step k - 1, so no process runs
  // more than a step ahead of another, and the clock's tick and the launcher's wake-ups leave the
  // loop (docs/results/loop-profile.md); a process alone in its scene knows what it wrote
  // and acknowledges nothing. The launcher hears each process's progress on its own topic every
  // 0.1 s of wall time and at the last step, for progress and hang detection. The first process
  // publishes /clock for outside tools. After the last step it waits, like a process of the
  // launcher's clock, until the launcher stops it.
  int runOwnClock(const std::atomic<bool>& stop) {
    const std::int64_t last = lastStep(scene_.clock);
    const auto wall_start = SteadyClock::now();
    next_progress_ = wall_start;
    TopicCounts expected;  // written by the end of the previous step
    for (std::int64_t step = 0; last < 0 || step <= last; ++step) {
      const Time t{step * scene_.clock.step.ns};
      if (!paceTo(wall_start, t, scene_.clock.real_time_factor, stop)) return 0;
      protocol_->publishClock(t);
      state_.now = t;
      const StepOutcome outcome = ownStep(step, step == last, expected, stop);
      if (outcome != StepOutcome::kDone) return exitCodeOf(outcome);
    }
    while (!stop) state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::milliseconds(100));
    return 0;
  }

  // One step of a process that steps itself, at state_.now: the other processes' acknowledgements
  // of the step before, the samples and timers, this process's acknowledgement and, now and then,
  // its progress. `expected` holds the counts of the step before and, alone, becomes this step's.
  StepOutcome ownStep(std::int64_t step, bool last_step, TopicCounts& expected, const std::atomic<bool>& stop) {
    const Time t = state_.now;
    const bool alone = protocol_->alone();
    if (!alone && !protocol_->awaitAcks(step - 1, expected, stop)) {
      if (stop) return StepOutcome::kStopped;
      protocol_->reportProgress(step, t);  // the failure, naming the processes this one waited for
      return StepOutcome::kFailed;
    }
    const bool ok = delivery_.deliver(&expected, giveUpOn(stop));
    if (!ok && stop) return StepOutcome::kStopped;
    if (!alone) protocol_->sendAck(step, t);
    if (!ok || last_step || SteadyClock::now() >= next_progress_) {
      protocol_->reportProgress(step, t);
      next_progress_ = SteadyClock::now() + std::chrono::milliseconds(100);
    }
    if (!ok) return StepOutcome::kFailed;
    if (alone) expected = protocol_->writtenSoFar();
    return StepOutcome::kDone;
  }

  int runRealtime(const std::atomic<bool>& stop) {
    while (!stop) {
      state_.now = wallNow();
      Time next = Time{state_.now.ns + 100'000'000};  // wake at least every 100 ms to check `stop`
      for (const auto& t : state_.timers) {
        if (t.next.ns >= 0 && t.next < next) next = t.next;
      }
      if (next > state_.now)
        state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::nanoseconds((next - state_.now).ns));
      state_.now = wallNow();
      if (!delivery_.deliver(nullptr, [] { return false; })) return 1;
    }
    return 0;
  }

  const Scene& scene_;
  std::string process_;
  std::string output_directory_;
  bool own_clock_;
  DdsNode dds_;
  std::unique_ptr<DdsNode> serialized_dds_;  // declared after dds_: destroyed before it
  ProcessState state_;
  Logger log_;
  ComponentGroup components_;
  StepDelivery delivery_;
  std::unique_ptr<LockstepProtocol> protocol_;  // in lockstep, once the components are built
  SteadyClock::time_point next_progress_;       // runOwnClock: when to tell the launcher again
};

}  // namespace
}  // namespace process

int runProcessGroup(const Scene& scene, const std::string& process, const std::string& output_directory,
                    const std::atomic<bool>& stop, bool own_clock) {
  try {
    process::ProcessRunner runner(scene, process, output_directory, own_clock);
    return runner.run(stop);
  } catch (const std::exception& e) {
    Logger(process, {}).error(e.what());
    return 1;
  }
}

}  // namespace uampc
