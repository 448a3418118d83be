#include "lockstep_clock.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <thread>

#include "uampc/msgs/rosgraph_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/run_files/run_directory.hpp"
#include "uampc/run_files/run_progress.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/lockstep_topics.hpp"
#include "wakeup.hpp"

namespace uampc {

using namespace eprosima::fastdds::dds;
using SteadyClock = std::chrono::steady_clock;

namespace {

// Progress on long runs: one line every few seconds (or a line rewritten in place on a terminal)
// for people and, when the environment names a file (run_files::kProgressFileVariable, set by
// `uampc experiment`), progress.json for programs, rewritten every second.
class Progress {
 public:
  explicit Progress(double duration_s) : duration_s_(duration_s), tty_(isatty(STDERR_FILENO)) {
    if (const char* file = std::getenv(run_files::kProgressFileVariable)) progress_file_ = file;
  }
  // last: the clock's final figures, written whatever the time since the previous ones.
  void update(double sim_s, double wall_s, bool last = false) {
    const auto now = SteadyClock::now();
    if (last || now - last_file_ >= std::chrono::seconds(1)) {
      last_file_ = now;
      writeFile({sim_s, std::max(duration_s_, 0.0), wall_s, last});
    }
    if (!last && now - last_line_ < std::chrono::seconds(tty_ ? 1 : 10)) return;
    last_line_ = now;
    const double factor = wall_s > 0 ? sim_s / wall_s : 0.0;
    if (duration_s_ > 0) {
      std::fprintf(stderr, "%suampc: sim %.1f / %.1f s (%3.0f%%), %.1fx real time%s", tty_ ? "\r" : "", sim_s,
                   duration_s_, 100.0 * sim_s / duration_s_, factor, tty_ ? "   " : "\n");
    } else {
      std::fprintf(stderr, "%suampc: sim %.1f s, %.1fx real time%s", tty_ ? "\r" : "", sim_s, factor,
                   tty_ ? "   " : "\n");
    }
    std::fflush(stderr);
  }
  void finish() {
    if (tty_) std::fprintf(stderr, "\n");
  }

 private:
  // A file that cannot be written is said once and given up: the run itself goes on.
  void writeFile(const run_files::RunProgress& progress) {
    if (progress_file_.empty()) return;
    try {
      run_files::writeRunProgress(progress_file_, progress);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "uampc: no more progress to %s: %s\n", progress_file_.c_str(), e.what());
      progress_file_.clear();
    }
  }

  double duration_s_;
  bool tty_;
  std::string progress_file_;  // empty: none
  SteadyClock::time_point last_line_{}, last_file_{};
};

// Each process of the scene writes step acknowledgements with one writer. More writers mean another
// lockstep run (or a stranger) on this domain: its clock ticks, acknowledgements and samples would
// mix with ours, so the run stops and says so instead of waiting for acknowledgements in vain.
// writers: how many the scene has on the topic (a writer per process, and on the progress topic
// the launcher's own marker, below).
std::string otherRunOnTheDomain(DataReader* ack_reader, const char* topic, std::size_t writers, int domain_id) {
  SubscriptionMatchedStatus status;
  ack_reader->get_subscription_matched_status(status);
  // total_count, not current_count: a writer seen even briefly (a second run that gave up) counts.
  if (status.total_count <= static_cast<int>(writers)) return {};
  return anotherRunOnTheDomain(domain_id, std::to_string(status.total_count) + " writers of step acknowledgements (" +
                                              topic + ") where this scene has " + std::to_string(writers));
}

// The acknowledgements the clock reads: takes what arrived and hands each valid one of a process of
// the scene to `on_ack`. Returns why the run must stop (a process that failed, another run on the
// domain), empty if nothing.
class AckFollower {
 public:
  AckFollower(const Scene& scene, DataReader* reader, const char* topic, std::size_t writers)
      : scene_(scene), reader_(reader), topic_(topic), writers_(writers), processes_(scene.processes()) {}

  template <class OnAck>
  std::string take(OnAck&& on_ack) {
    if (std::string other = otherRunOnTheDomain(reader_, topic_, writers_, scene_.domain_id); !other.empty()) {
      stayUntilTheOtherRunNotices();
      return other;
    }
    uampc::msg::StepAck ack;
    SampleInfo info;
    while (reader_->take_next_sample(&ack, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      if (std::find(processes_.begin(), processes_.end(), ack.process()) == processes_.end()) continue;
      // A process is known by the writer of its ready message (step -1, its first). Anything else
      // under its name is another run's on this domain: a second ready says so; a later step from
      // an unknown writer is left alone (processes that step themselves may be far into a run
      // this side never started), until the writers' count gives the other run away.
      auto known = writer_of_.find(ack.process());
      if (ack.step() < 0) {
        if (known != writer_of_.end() && known->second != info.publication_handle) {
          stayUntilTheOtherRunNotices();
          return anotherRunOnTheDomain(scene_.domain_id, "two processes named '" + ack.process() + "' said ready");
        }
        writer_of_[ack.process()] = info.publication_handle;
      } else if (known == writer_of_.end() || known->second != info.publication_handle) {
        continue;
      }
      if (ack.failed()) return "process '" + ack.process() + "': " + ack.message();
      on_ack(ack);
    }
    return {};
  }

  const std::vector<std::string>& processes() const { return processes_; }

 private:
  const Scene& scene_;
  DataReader* reader_;
  const char* topic_;
  std::size_t writers_;
  std::vector<std::string> processes_;
  std::map<std::string, InstanceHandle_t> writer_of_;  // each process's writer, from its ready message
};

std::string noAcknowledgement(const char* what, const std::string& late, SteadyClock::duration timeout) {
  return std::string("no ") + what + " from process(es) " + late + " within " +
         std::to_string(std::chrono::duration<double>(timeout).count()) +
         " s of wall time (clock.ack_timeout; at least 30 s at the start); a component is hung or far too slow (at the "
         "start, a large point map may still be building: raise clock.ack_timeout, or coarsen "
         "world.point_map_resolution)";
}

}  // namespace

bool paceTo(SteadyClock::time_point wall_start, Time t, double factor, const std::atomic<bool>& stop) {
  if (factor <= 0) return !stop;
  const auto due =
      wall_start + std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(t.seconds() / factor));
  while (!stop && SteadyClock::now() < due) {
    std::this_thread::sleep_until(std::min(due, SteadyClock::now() + std::chrono::milliseconds(100)));
  }
  return !stop;
}

std::int64_t lastStep(const ClockSettings& clock) {
  if (clock.duration_s <= 0) return -1;
  return Time::fromSeconds(clock.duration_s).ns / clock.step.ns;
}

namespace {

// One run of the clock, in named steps: wait for every process's ready message, then either tick
// /clock step by step (the clock here) or follow processes that step themselves.
class ClockRun {
 public:
  ClockRun(const Scene& scene, const std::atomic<bool>& stop, const std::function<std::string()>& check_processes,
           ClockHost host)
      : scene_(scene),
        stop_(stop),
        check_processes_(check_processes),
        dds_(scene.domain_id, scene.dds_profile, true, "uampc/clock",
             securityIdentity(scene.security_directory, kLauncherIdentity)),
        // With the clock in the process, /clock is that process's to write.
        clock_writer_(host == ClockHost::kHere
                          ? dds_.createWriter(kClockTopic, MessageType<rosgraph_msgs::msg::Clock>::kRosName,
                                              &detail::makeTypeSupport<rosgraph_msgs::msg::Clock>, QosPreset::kControl)
                          : nullptr),
        // Processes that step themselves report their progress apart from the acknowledgements
        // they exchange every step, which this side does not need.
        ack_topic_(host == ClockHost::kHere ? kStepAckTopic : kStepProgressTopic),
        ack_reader_(dds_.createReader(ack_topic_, MessageType<uampc::msg::StepAck>::kRosName,
                                      &detail::makeTypeSupport<uampc::msg::StepAck>, QosPreset::kControl, &listener_)),
        // Following, this side writes nothing another run would hear (the ticking clock's /clock
        // writer is how its processes notice a second run): a writer on the progress topic, never
        // written, makes a second launcher one writer too many for the first, at once, whether or
        // not its processes got far enough to write anything.
        presence_(host == ClockHost::kInTheProcess
                      ? dds_.createWriter(kStepProgressTopic, MessageType<uampc::msg::StepAck>::kRosName,
                                          &detail::makeTypeSupport<uampc::msg::StepAck>, QosPreset::kControl)
                      : nullptr),
        acks_(scene, ack_reader_, ack_topic_, scene.processes().size() + (presence_ ? 1 : 0)),
        processes_(acks_.processes()),
        ack_timeout_(std::chrono::duration_cast<SteadyClock::duration>(
            std::chrono::duration<double>(scene.clock.ack_timeout_s))),
        clock_start_(SteadyClock::now()) {
    // The latest step each process acknowledged: a process that steps itself may have run far, even
    // to its end, before its ready message is read here.
    for (const auto& p : scene.processes()) process_step_[p] = -1;
  }

  ~ClockRun() {
    if (clock_writer_) dds_.deleteWriter(clock_writer_);
    if (presence_) dds_.deleteWriter(presence_);
    dds_.deleteReader(ack_reader_);
  }

  ClockResult run() {
    if (!waitFor(-1, "ready message")) {
      result_.ok = false;
      return result_;
    }
    waitUntilTheClockReadersMatch();
    // The loop's wall time starts here: the start (processes building worlds, DDS discovery) is
    // reported on its own, so that the real-time factor says how fast the loop runs, and pacing
    // (real_time_factor) does not rush the first steps to make up for a slow start.
    wall_start_ = SteadyClock::now();
    result_.startup_seconds = std::chrono::duration<double>(wall_start_ - clock_start_).count();
    if (clock_writer_)
      tickEveryStep();
    else
      followSelfSteppingProcesses();
    if (result_.error == "stopped") result_.error.clear();
    result_.wall_seconds = std::chrono::duration<double>(SteadyClock::now() - wall_start_).count();
    progress_.update(result_.sim_seconds, result_.wall_seconds, true);
    progress_.finish();
    return result_;
  }

 private:
  // Every wait ends on a failure: an error, a process gone, the deadline passed. `late` names the
  // processes waited for, asked only when the deadline has passed.
  std::string waitProblem(SteadyClock::time_point deadline, const std::function<std::string()>& late, const char* what,
                          SteadyClock::duration timeout) {
    if (std::string problem = check_processes_(); !problem.empty()) {
      // A process that failed said why in an acknowledgement it delivered before exiting, which
      // may have arrived since the last take: its reason, not just its exit status.
      if (std::string reported = acks_.take([](const uampc::msg::StepAck&) {}); !reported.empty()) return reported;
      return problem;
    }
    if (SteadyClock::now() > deadline) return noAcknowledgement(what, late(), timeout);
    listener_.waitUntil(std::min(deadline, SteadyClock::now() + std::chrono::milliseconds(50)));
    return {};
  }

  // Records a process's step; false if it is not news.
  bool note(const uampc::msg::StepAck& ack) {
    std::int64_t& step = process_step_[ack.process()];
    if (ack.step() <= step) return false;
    step = ack.step();
    return true;
  }

  // Waits until every process acknowledged `step`; false (with result_.error) on failure.
  bool waitFor(std::int64_t step, const char* what) {
    std::set<std::string> acked;
    const auto timeout = step < 0 ? std::chrono::duration_cast<SteadyClock::duration>(
                                        std::chrono::duration<double>(scene_.clock.startupTimeout()))
                                  : ack_timeout_;
    const auto deadline = SteadyClock::now() + timeout;
    auto late = [&] {
      std::string names;
      for (const auto& p : processes_) {
        if (!acked.count(p)) names += (names.empty() ? "" : ", ") + p;
      }
      return names;
    };
    for (;;) {
      result_.error = acks_.take([&](const uampc::msg::StepAck& ack) {
        if (ack.step() >= step) acked.insert(ack.process());  // later: a process with the clock inside
        note(ack);
      });
      if (!result_.error.empty()) return false;
      if (acked.size() == processes_.size()) return true;
      if (stop_) {
        result_.error = "stopped";
        return false;
      }
      result_.error = waitProblem(deadline, late, what, timeout);
      if (!result_.error.empty()) return false;
    }
  }

  // The processes' clock readers are matched (they said ready); make sure this side sees them too.
  void waitUntilTheClockReadersMatch() {
    while (clock_writer_) {
      PublicationMatchedStatus s;
      clock_writer_->get_publication_matched_status(s);
      if (s.current_count >= static_cast<int>(processes_.size())) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  void reached(Time t) {
    result_.sim_seconds = t.seconds();
    result_.wall_seconds = std::chrono::duration<double>(SteadyClock::now() - wall_start_).count();
    progress_.update(result_.sim_seconds, result_.wall_seconds);
  }

  // The clock here: /clock ticks each step once every process acknowledged the one before.
  void tickEveryStep() {
    const std::int64_t last = lastStep(scene_.clock);
    for (std::int64_t step = 0; last < 0 || step <= last; ++step) {
      const Time t{step * scene_.clock.step.ns};
      if (!paceTo(wall_start_, t, scene_.clock.real_time_factor, stop_)) break;
      rosgraph_msgs::msg::Clock tick;
      tick.clock(toMsg(t));
      clock_writer_->write(&tick);
      if (!waitFor(step, "acknowledgement of the step")) {
        result_.ok = result_.error == "stopped";
        break;
      }
      reached(t);
    }
  }

  std::int64_t slowestStep() const {
    std::int64_t step = std::numeric_limits<std::int64_t>::max();
    for (const auto& [p, s] : process_step_) step = std::min(step, s);
    return step;
  }

  // The processes at the slowest step, comma-separated: those a stuck run waits for.
  std::string slowestProcesses() const {
    std::string late;
    for (const auto& [p, step] : process_step_) {
      if (step == slowestStep()) late += (late.empty() ? "" : ", ") + p;
    }
    return late;
  }

  // The processes step themselves and report their progress every 0.1 s of wall time and at their
  // last step. Each report that moves a process on resets the deadline, so that a hung component
  // is named after clock.ack_timeout as with the clock here. The run has reached the step of the
  // slowest process; it ends when every process has reported the last step.
  void followSelfSteppingProcesses() {
    const std::int64_t last = lastStep(scene_.clock);
    // With several processes, one that waits in vain for another's acknowledgement gives up at
    // 0.9 x ack_timeout and names it; this side waits longer, so that such a report comes first,
    // and names the slowest only when none came (every process stuck).
    const auto follow_timeout = processes_.size() > 1 ? ack_timeout_ + ack_timeout_ / 2 : ack_timeout_;
    auto deadline = wall_start_ + follow_timeout;
    std::int64_t reached_step = -1;
    auto progress_made = [&] {
      if (slowestStep() <= reached_step) return;
      reached_step = slowestStep();
      reached(Time{reached_step * scene_.clock.step.ns});
    };
    auto follow = [&](const uampc::msg::StepAck& ack) {
      if (!note(ack)) return;
      deadline = SteadyClock::now() + follow_timeout;
      progress_made();
    };
    progress_made();  // a process may have run on while the others were read ready
    while (!stop_ && (last < 0 || slowestStep() < last)) {
      result_.error = acks_.take(follow);
      if (result_.error.empty() && (last < 0 || slowestStep() < last))
        result_.error = waitProblem(
            deadline, [this] { return slowestProcesses(); }, "acknowledgement of a step", follow_timeout);
      if (!result_.error.empty()) {
        result_.ok = false;
        break;
      }
    }
  }

  const Scene& scene_;
  const std::atomic<bool>& stop_;
  const std::function<std::string()>& check_processes_;
  ClockResult result_;
  // Declared before the participant, so that it outlives the reader it listens to: Fast DDS may
  // call it until the reader is deleted (ThreadSanitizer saw a notify on a destroyed Wakeup).
  Wakeup listener_;
  DdsNode dds_;
  DataWriter* clock_writer_;
  const char* ack_topic_;
  DataReader* ack_reader_;
  DataWriter* presence_;
  AckFollower acks_;
  const std::vector<std::string>& processes_;
  std::map<std::string, std::int64_t> process_step_;
  const SteadyClock::duration ack_timeout_;
  const SteadyClock::time_point clock_start_;
  SteadyClock::time_point wall_start_;
  Progress progress_{scene_.clock.duration_s};
};

}  // namespace

std::string anotherRunOnTheDomain(int domain_id, const std::string& evidence) {
  return "another lockstep run is on DDS domain " + std::to_string(domain_id) + ": " + evidence +
         "; two runs on one domain hear each other's clock and topics, so give each run its own domain_id "
         "(--set domain_id=N)";
}

void stayUntilTheOtherRunNotices() { std::this_thread::sleep_for(std::chrono::milliseconds(1500)); }

// A participant Fast DDS refuses (DDS Security's certificates, a profile's transports) is a failed
// run with its reason, not an exception out of the launcher.
ClockResult runLockstepClock(const Scene& scene, const std::atomic<bool>& stop,
                             const std::function<std::string()>& check_processes, ClockHost host) {
  try {
    return ClockRun(scene, stop, check_processes, host).run();
  } catch (const std::exception& e) {
    ClockResult result;
    result.ok = false;
    result.error = std::string("the lockstep clock: ") + e.what();
    return result;
  }
}

}  // namespace uampc
