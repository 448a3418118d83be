// The lockstep protocol as one process group speaks it (process_group.cpp runs its steps with it).
#pragma once

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/scene.hpp"
#include "uampc/runtime/time.hpp"
#include "process_state.hpp"

namespace uampc::process {

class DdsWriter;

// The lockstep protocol as one process speaks it (docs/dev/time-and-lockstep.md): the launcher's
// ticks on /clock, or this process's own /clock when it steps itself; its acknowledgements of each
// step with the samples it wrote, to the clock and the other processes; its progress, to the
// launcher; the other processes' acknowledgements; and another run on the domain, noticed.
class LockstepProtocol {
 public:
  // Opens the protocol's topics. They are reliable and keep every sample, like the loop's own.
  LockstepProtocol(const Scene& scene, const std::string& process, bool own_clock, DdsNode& dds, ProcessState& state,
                   const Logger& log);

  ~LockstepProtocol();

  // Alone in its scene: no other process's acknowledgements to wait for.
  bool alone() const { return !ack_reader_; }

  // The protocol's endpoints discovery has not matched yet, one line each; empty when all are.
  std::string unmatched() const;

  // The ready message (step -1), to whoever hears this process's acknowledgements and progress.
  void sayReady();

  // The times the launcher's clock has ticked since the last call.
  std::vector<Time> takeTicks();

  // Whether the launcher's clock (or `uampc clock`) has left the domain: no writer of /clock is
  // matched any more. Meaningful once the start matched it.
  bool clockLeft() const;

  // /clock for outside tools, if this process publishes it.
  void publishClock(Time t);

  // The acknowledgement of a step, to the launcher's clock and the other processes.
  void sendAck(std::int64_t step, Time stamp);

  // How far a process that steps itself is, to the launcher.
  void reportProgress(std::int64_t step, Time stamp);

  // Before a failed lockstep process exits (run(), on any failure): its last acknowledgement, which
  // says why, is in its readers' hands. Otherwise the launcher may see the exit first and report
  // only "exited with status 1" (seen in CI). Bounded: a reader that is gone does not keep the
  // process; without acknowledgement writers (a failure before they exist) a no-op.
  void deliverFailure();

  // The acknowledgements of step `step` from every process, summed into the number of samples
  // written on each topic; false on timeout or stop.
  bool awaitAcks(std::int64_t step, TopicCounts& expected, const std::atomic<bool>& stop);

  // While waiting: another run on the domain is a failure, said once the other run may have noticed.
  bool anotherRunStops();

  // The samples this process has written on each topic so far.
  TopicCounts writtenSoFar() const;

 private:
  std::unique_ptr<DdsWriter> stepAckWriter(const char* topic);

  // The counts an acknowledgement of `step` carries. The ready message (step -1) counts nothing:
  // samples written while the components were constructed (latched ones) carry time 0 and are
  // delivered at step 1, counted by step 0's acknowledgement.
  std::vector<uampc::msg::TopicCount> writtenBy(std::int64_t step) const;

  uampc::msg::StepAck ackOf(std::int64_t step, Time stamp) const;

  // Keeps every acknowledgement that arrived, by process and step.
  void takeAcks();

  // The processes whose acknowledgement of `step` has not arrived, comma-separated. A faster process
  // may already have acknowledged later steps; the counts must be those of exactly this step.
  std::string notAcknowledged(std::int64_t step) const;

  // The samples every process wrote by the end of `step`, summed per topic; older steps are
  // forgotten, as they are not needed again.
  TopicCounts countsOf(std::int64_t step);

  // Another lockstep run on this domain, whose ticks would drive this one or whose acknowledgements
  // would mix with its own: a second writer of /clock ever, or more writers of acknowledgements than
  // the scene has processes (the launcher checks its readers the same way).
  std::string anotherRun() const;

  const Scene& scene_;
  const std::string& process_;
  const bool own_clock_;
  DdsNode& dds_;
  ProcessState& state_;
  const Logger& log_;
  std::unique_ptr<ProtocolReader> clock_reader_;                // ticks of the launcher's clock
  eprosima::fastdds::dds::DataWriter* clock_writer_ = nullptr;  // or this process's own (own_clock_)
  std::unique_ptr<DdsWriter> ack_writer_;                       // to the launcher's clock and the other processes
  std::unique_ptr<DdsWriter> progress_writer_;                  // to the launcher, when the process steps itself
  std::unique_ptr<ProtocolReader> ack_reader_;
  // Acknowledged sample counts: process -> step -> counts per topic.
  std::map<std::string, std::map<std::int64_t, std::vector<uampc::msg::TopicCount>>> acks_;
};

}  // namespace uampc::process
