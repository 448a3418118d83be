#include "lockstep_protocol.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>

#include <chrono>
#include <deque>

#include "uampc/msgs/rosgraph_msgs.hpp"
#include "uampc/runtime/lockstep_topics.hpp"
#include "uampc/runtime/message_type.hpp"
#include "../lockstep_clock.hpp"
#include "dds_writer.hpp"
#include "unmatched_ports.hpp"

namespace uampc::process {

using namespace eprosima::fastdds::dds;
using SteadyClock = std::chrono::steady_clock;

LockstepProtocol::LockstepProtocol(const Scene& scene, const std::string& process, bool own_clock, DdsNode& dds,
                                   ProcessState& state, const Logger& log)
    : scene_(scene), process_(process), own_clock_(own_clock), dds_(dds), state_(state), log_(log) {
  // Processes that step themselves: the first of the scene publishes /clock, for outside tools.
  if (own_clock_ && scene_.processes().front() == process_) {
    clock_writer_ = dds_.createWriter(kClockTopic, MessageType<rosgraph_msgs::msg::Clock>::kRosName,
                                      &detail::makeTypeSupport<rosgraph_msgs::msg::Clock>, QosPreset::kControl);
  } else if (!own_clock_) {
    clock_reader_ =
        std::make_unique<ProtocolReader>(dds_, kClockTopic, MessageType<rosgraph_msgs::msg::Clock>::kRosName,
                                         &detail::makeTypeSupport<rosgraph_msgs::msg::Clock>, &state_.wakeup);
  }
  // Every process reads every acknowledgement: they say how many samples to wait for. A process
  // alone in its scene knows what it wrote: its acknowledgements go to the clock only (a delivery
  // to itself cost about as much as one to the clock, every step), and if it steps itself, to
  // nobody: the launcher hears its progress.
  const bool alone = scene_.processes().size() == 1;
  if (!own_clock_ || !alone) ack_writer_ = stepAckWriter(kStepAckTopic);
  if (own_clock_) progress_writer_ = stepAckWriter(kStepProgressTopic);
  if (!alone)
    ack_reader_ = std::make_unique<ProtocolReader>(dds_, kStepAckTopic, MessageType<uampc::msg::StepAck>::kRosName,
                                                   &detail::makeTypeSupport<uampc::msg::StepAck>, &state_.wakeup);
}

LockstepProtocol::~LockstepProtocol() {
  clock_reader_.reset();
  if (clock_writer_) dds_.deleteWriter(clock_writer_);
  ack_writer_.reset();
  progress_writer_.reset();
  ack_reader_.reset();
}

bool LockstepProtocol::clockLeft() const {
  if (!clock_reader_) return false;
  SubscriptionMatchedStatus clock_status;
  clock_reader_->shared.reader->get_subscription_matched_status(clock_status);
  return clock_status.current_count < 1;
}

std::string LockstepProtocol::unmatched() const {
  std::string missing;
  if (clock_reader_) {
    SubscriptionMatchedStatus clock_status;
    clock_reader_->shared.reader->get_subscription_matched_status(clock_status);
    if (clock_status.current_count < 1) missing += "\n  the lockstep clock";
  }
  const int processes = static_cast<int>(scene_.processes().size());
  // The launcher's clock reads the acknowledgements, or (processes that step themselves) the
  // progress; the processes read each other's acknowledgements.
  if (ack_writer_) {
    PublicationMatchedStatus ack_status;
    ack_writer_->dds()->get_publication_matched_status(ack_status);
    if (ack_status.current_count < (own_clock_ ? 0 : 1) + (ack_reader_ ? processes : 0))
      missing += "\n  the acknowledgement readers";
  }
  if (progress_writer_) {
    PublicationMatchedStatus progress_status;
    progress_writer_->dds()->get_publication_matched_status(progress_status);
    if (progress_status.current_count < 1) missing += "\n  the launcher";
  }
  if (ack_reader_) {
    SubscriptionMatchedStatus ack_reader_status;
    ack_reader_->shared.reader->get_subscription_matched_status(ack_reader_status);
    if (ack_reader_status.current_count < processes) missing += "\n  the other processes' acknowledgements";
  }
  return missing;
}

void LockstepProtocol::sayReady() {
  if (ack_writer_) sendAck(-1, Time{0});
  if (progress_writer_) reportProgress(-1, Time{0});
}

std::vector<Time> LockstepProtocol::takeTicks() {
  std::deque<Sample> ticks;
  clock_reader_->takeAll(ticks);
  std::vector<Time> times;
  for (const auto& tick : ticks)
    times.push_back(fromMsg(static_cast<const rosgraph_msgs::msg::Clock*>(tick.data.get())->clock()));
  return times;
}

void LockstepProtocol::publishClock(Time t) {
  if (!clock_writer_) return;
  rosgraph_msgs::msg::Clock tick;
  tick.clock(toMsg(t));
  clock_writer_->write(&tick);
}

void LockstepProtocol::sendAck(std::int64_t step, Time stamp) {
  uampc::msg::StepAck ack = ackOf(step, stamp);
  // Alone under the launcher's clock: what the others would have read (with the clock inside,
  // runOwnClock keeps its counts itself).
  if (!ack_reader_ && !own_clock_) acks_[process_][step] = ack.written();
  ack_writer_->write(&ack);
}

void LockstepProtocol::reportProgress(std::int64_t step, Time stamp) {
  uampc::msg::StepAck ack = ackOf(step, stamp);
  progress_writer_->write(&ack);
}

void LockstepProtocol::deliverFailure() {
  const eprosima::fastrtps::Duration_t patience(1, 0);
  for (DdsWriter* writer : {ack_writer_.get(), progress_writer_.get()}) {
    if (writer) writer->dds()->wait_for_acknowledgments(patience);
  }
}

bool LockstepProtocol::awaitAcks(std::int64_t step, TopicCounts& expected, const std::atomic<bool>& stop) {
  // A little before the clock gives up: the clock then hears from this process which peer it
  // waited for (a stopped process), instead of naming every process as late. At the start (step
  // -1) the clock waits for discovery as long as startupTimeout() says, and so must this side.
  const double patience_s = 0.9 * (step < 0 ? scene_.clock.startupTimeout() : scene_.clock.ack_timeout_s);
  const auto deadline = SteadyClock::now() + std::chrono::duration<double>(patience_s);
  for (;;) {
    takeAcks();
    const std::string missing = notAcknowledged(step);
    if (missing.empty()) break;
    if (stop || anotherRunStops()) return false;
    if (SteadyClock::now() > deadline) {
      state_.failure = "acknowledgements of step " + std::to_string(step) + " from process(es) " + missing +
                       " did not arrive within " + std::to_string(patience_s) + " s" +
                       (step < 0 ? securedStartHint(scene_) : std::string());
      log_.error(state_.failure);
      return false;
    }
    state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::milliseconds(10));
  }
  expected = countsOf(step);
  return true;
}

bool LockstepProtocol::anotherRunStops() {
  state_.failure = anotherRun();
  if (state_.failure.empty()) return false;
  log_.error(state_.failure);
  stayUntilTheOtherRunNotices();
  return true;
}

TopicCounts LockstepProtocol::writtenSoFar() const {
  TopicCounts written;
  for (const auto& w : state_.writers) written[w->topic()] += w->written();
  return written;
}

std::unique_ptr<DdsWriter> LockstepProtocol::stepAckWriter(const char* topic) {
  return std::make_unique<DdsWriter>(
      dds_,
      dds_.createWriter(topic, MessageType<uampc::msg::StepAck>::kRosName,
                        &detail::makeTypeSupport<uampc::msg::StepAck>, QosPreset::kControl),
      topic, QosPreset::kControl, state_);
}

std::vector<uampc::msg::TopicCount> LockstepProtocol::writtenBy(std::int64_t step) const {
  std::vector<uampc::msg::TopicCount> counts;
  if (step < 0) return counts;
  for (const auto& [topic, count] : writtenSoFar()) {
    uampc::msg::TopicCount c;
    c.topic(topic);
    c.count(count);
    counts.push_back(c);
  }
  return counts;
}

uampc::msg::StepAck LockstepProtocol::ackOf(std::int64_t step, Time stamp) const {
  uampc::msg::StepAck ack;
  ack.process(process_);
  ack.step(step);
  ack.stamp(toMsg(stamp));
  ack.written() = writtenBy(step);
  ack.failed(!state_.failure.empty());
  ack.message(state_.failure);
  return ack;
}

void LockstepProtocol::takeAcks() {
  std::deque<Sample> acks;
  if (ack_reader_) ack_reader_->takeAll(acks);
  for (const auto& a : acks) {
    const auto* ack = static_cast<const uampc::msg::StepAck*>(a.data.get());
    acks_[ack->process()][ack->step()] = ack->written();
  }
}

std::string LockstepProtocol::notAcknowledged(std::int64_t step) const {
  std::string missing;
  for (const auto& p : scene_.processes()) {
    auto it = acks_.find(p);
    if (it == acks_.end() || !it->second.count(step)) missing += (missing.empty() ? "" : ", ") + p;
  }
  return missing;
}

TopicCounts LockstepProtocol::countsOf(std::int64_t step) {
  TopicCounts expected;
  for (auto& [process, by_step] : acks_) {
    for (const auto& c : by_step.at(step)) expected[c.topic()] += c.count();
    by_step.erase(by_step.begin(), by_step.find(step));
  }
  return expected;
}

std::string LockstepProtocol::anotherRun() const {
  SubscriptionMatchedStatus status;
  if (clock_reader_) {
    clock_reader_->shared.reader->get_subscription_matched_status(status);
    if (status.total_count > 1)
      return anotherRunOnTheDomain(scene_.domain_id,
                                   std::to_string(status.total_count) + " clocks were heard on " + kClockTopic);
  }
  // The acknowledgements' writers as matched now: a writer discovered again counts twice in
  // total_count (seen at the start of runs with the launcher's clock).
  if (ack_reader_) {
    ack_reader_->shared.reader->get_subscription_matched_status(status);
    const auto processes = static_cast<int>(scene_.processes().size());
    if (status.current_count > processes)
      return anotherRunOnTheDomain(scene_.domain_id, std::to_string(status.current_count) +
                                                         " writers of step acknowledgements where the scene has " +
                                                         std::to_string(processes) + " process(es)");
  }
  return {};
}

}  // namespace uampc::process
