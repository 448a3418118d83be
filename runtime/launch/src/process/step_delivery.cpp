#include "step_delivery.hpp"

#include <chrono>
#include <cstdint>
#include <exception>
#include <utility>

namespace uampc::process {

using SteadyClock = std::chrono::steady_clock;

bool StepDelivery::guarded(const std::string& component, const char* what, const std::function<void()>& work) {
  try {
    work();
    return true;
  } catch (const std::exception& e) {
    state_.failure = "component '" + component + "' failed in " + what +
                     " at t=" + std::to_string(state_.now.seconds()) + " s: " + e.what();
    log_.error(state_.failure);
    return false;
  }
}

bool StepDelivery::deliverInputs(const TopicCounts* expected, const std::function<bool()>& give_up) {
  for (auto& reader : state_.dds_readers) reader->poll();  // once per reader, not per port
  for (auto& r : state_.readers) {
    std::deque<Sample> samples;
    samples.swap(r->deferred);
    r->drainInbox(samples);
    if (expected && !awaitSamples(*r, samples, *expected, give_up)) return false;
    for (auto& s : samples) {
      if (state_.lockstep && s.source_time >= state_.now) {
        r->deferred.push_back(std::move(s));
        continue;
      }
      ++r->delivered;
      if (!guarded(r->component, ("input '" + r->port + "' (" + r->topic + ")").c_str(),
                   [&] { r->callback(s.data.get(), s.source_time); })) {
        return false;
      }
    }
  }
  return true;
}

bool StepDelivery::awaitSamples(ReaderPort& r, std::deque<Sample>& samples, const TopicCounts& expected,
                                const std::function<bool()>& give_up) {
  auto it = expected.find(r.topic);
  const std::uint64_t want = it == expected.end() ? 0 : it->second;
  const auto deadline = SteadyClock::now() + std::chrono::duration<double>(scene_.clock.ack_timeout_s);
  for (;;) {
    std::uint64_t have = r.delivered;
    for (const auto& s : samples) have += s.source_time < state_.now ? 1 : 0;
    if (have >= want) return true;
    // Stopped (Ctrl-C, or the launcher died): the samples may never come; not a failure.
    if (give_up()) return false;
    if (SteadyClock::now() > deadline) {
      state_.failure = "input '" + r.port + "' of component '" + r.component + "' (" + r.topic + ") expected " +
                       std::to_string(want) + " samples by t=" + std::to_string(state_.now.seconds()) +
                       " s but got " + std::to_string(have) + " within " +
                       std::to_string(scene_.clock.ack_timeout_s) + " s";
      log_.error(state_.failure);
      return false;
    }
    state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::milliseconds(10));
    r.takeAll(samples);
  }
}

bool StepDelivery::fireTimers() {
  for (auto& t : state_.timers) {
    if (t.next.ns < 0) t.next = state_.now;  // first firing at the start of the run
    if (state_.now < t.next) continue;
    if (!guarded(t.component, "a timer", t.callback)) return false;
    // Keep the phase; skip periods that were missed entirely (real time under load).
    do {
      t.next = t.next + t.period;
    } while (t.next <= state_.now);
  }
  return true;
}

}  // namespace uampc::process
