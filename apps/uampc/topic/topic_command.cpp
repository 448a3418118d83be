#include "topic/topic_command.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "cli/command_set.hpp"
#include "topic/raw_subscription.hpp"
#include "topic/topic_discovery.hpp"
#include "topic/topic_statistics.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/runtime/cdr_decoder.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/edit_distance.hpp"
#include "uampc/runtime/idl_parser.hpp"
#include "uampc/runtime/message_definition.hpp"
#include "uampc/runtime/message_type.hpp"
#include "uampc/runtime/stop_signals.hpp"
#include "uampc/runtime/yaml_printer.hpp"

namespace uampc::app {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kNoWriter = 1;
constexpr int kBadEnvironment = 2;
// After the first writer of a topic appears, discovery runs this much longer so that the reader's
// QoS can match every writer, not only the first one seen.
constexpr auto kMoreWritersGrace = std::chrono::milliseconds(300);
constexpr auto kReportPeriod = std::chrono::seconds(1);

// Sleeps until `deadline`; false when a signal came first.
bool sleepUntil(Clock::time_point deadline) {
  while (Clock::now() < deadline) {
    if (stopRequested()) return false;
    std::this_thread::sleep_for(std::min<Clock::duration>(deadline - Clock::now(), std::chrono::milliseconds(20)));
  }
  return !stopRequested();
}

Clock::time_point after(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

std::string secondsText(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

// ---- list ----

std::string typesOf(const DiscoveredTopic& topic) {
  std::set<std::string> types;
  for (const auto* endpoints : {&topic.writers, &topic.readers}) {
    for (const DiscoveredEndpoint& e : *endpoints) types.insert(shownTypeName(e.type));
  }
  std::string text;
  for (const std::string& t : types) text += (text.empty() ? "" : " | ") + t;  // several: a mismatch worth seeing
  return text;
}

std::string endpointLine(const char* kind, const DiscoveredEndpoint& e,
                         const std::map<std::string, DiscoveredParticipant>& participants) {
  const auto p = participants.find(e.guid_prefix);
  const std::string name = p == participants.end()  ? "(participant not discovered)"
                           : p->second.name.empty() ? "(unnamed)"
                                                    : "'" + p->second.name + "'";
  const std::string vendor = p == participants.end() ? "" : "  vendor " + vendorText(p->second.vendor);
  const std::string who = name + " " + e.guid_prefix + vendor;
  return std::string("    ") + kind + "  " + who + "  " + (e.reliable ? "reliable" : "best-effort") + ", " +
         (e.transient_local ? "transient-local" : "volatile") + "\n";
}

void printList(const TopicDiscovery& discovery, bool verbose, int domain_id, double wait_s) {
  const auto topics = discovery.topics();
  const auto participants = discovery.participants();
  if (topics.empty()) {
    std::cout << "no topics on domain " << domain_id << " (discovery ran " << secondsText(wait_s) << " s)\n";
    return;
  }
  std::map<std::string, const DiscoveredTopic*> by_shown_name;
  std::size_t name_width = 0;
  std::size_t type_width = 0;
  for (const auto& [name, topic] : topics) {
    by_shown_name[shownTopicName(name)] = &topic;
    name_width = std::max(name_width, shownTopicName(name).size());
    type_width = std::max(type_width, typesOf(topic).size());
  }
  for (const auto& [name, topic] : by_shown_name) {
    std::cout << std::left << std::setw(static_cast<int>(name_width)) << name << "  "
              << std::setw(static_cast<int>(type_width)) << typesOf(*topic) << "  writers: " << topic->writers.size()
              << "  readers: " << topic->readers.size() << "\n";
    if (!verbose) continue;
    for (const DiscoveredEndpoint& w : topic->writers) std::cout << endpointLine("writer", w, participants);
    for (const DiscoveredEndpoint& r : topic->readers) std::cout << endpointLine("reader", r, participants);
  }
}

int list(const TopicOptions& options, int domain_id) {
  TopicDiscovery discovery(domain_id, checkedSecurityIdentity(options.security_dir, kObserverIdentity));
  sleepUntil(after(options.wait_s));  // Ctrl-C: list what was found so far
  printList(discovery, options.verbose, domain_id, options.wait_s);
  return 0;
}

// ---- echo, hz, bw: one topic ----

// The topic with its writers, once discovery has seen one; nullopt after wait_s or a signal.
std::optional<DiscoveredTopic> waitForWriter(const TopicDiscovery& discovery, const std::string& dds_topic,
                                             double wait_s) {
  const Clock::time_point deadline = after(wait_s);
  while (true) {
    const auto topics = discovery.topics();
    const auto found = topics.find(dds_topic);
    if (found != topics.end() && !found->second.writers.empty()) {
      if (!sleepUntil(Clock::now() + kMoreWritersGrace)) return std::nullopt;
      return discovery.topics().at(dds_topic);
    }
    if (Clock::now() >= deadline || !sleepUntil(std::min(deadline, Clock::now() + std::chrono::milliseconds(50)))) {
      return std::nullopt;
    }
  }
}

int noWriter(const TopicDiscovery& discovery, const TopicOptions& options, int domain_id) {
  std::cerr << "uampc topic: no writer of " << options.topic << " found on domain " << domain_id << " within "
            << secondsText(options.wait_s) << " s";
  std::vector<std::string> names;
  for (const auto& [name, topic] : discovery.topics()) {
    if (!topic.writers.empty()) names.push_back(shownTopicName(name));
  }
  const std::string closest = closestMatch(options.topic, names);
  if (!closest.empty()) std::cerr << "; did you mean " << closest << "?";
  std::cerr << "\n";
  return kNoWriter;
}

// How samples of a DDS type are decoded: by the structure of its IDL when this uampc has it.
struct Decoding {
  std::optional<MessageStructure> structure;
  std::string why_not;  // when there is no structure
};

Decoding decodingOf(const std::string& dds_type) {
  Decoding d;
  const std::string ros_type = rosTypeName(dds_type);
  try {
    if (!ros_type.empty()) d.structure = findMessageStructure(ros_type);
    if (!d.structure) d.why_not = "no message library loaded by uampc has it";
  } catch (const IdlError& e) {
    d.why_not = std::string("its IDL cannot be read: ") + e.what();
  }
  return d;
}

// Samples handed from Fast DDS's thread to the main one.
class SampleQueue {
 public:
  void push(SerializedMessage&& sample) {
    std::lock_guard<std::mutex> lock(mutex_);
    samples_.push_back(std::move(sample));
    ready_.notify_one();
  }

  // The samples that arrived, after waiting up to `timeout` for one.
  std::deque<SerializedMessage> takeAll(Clock::duration timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait_for(lock, timeout, [this] { return !samples_.empty(); });
    return std::exchange(samples_, {});
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<SerializedMessage> samples_;
};

void printSample(const SerializedMessage& sample, const Decoding& decoding, const TopicOptions& options) {
  if (!decoding.structure) {
    std::cout << "<" << sample.data.size() << " bytes>\n";
  } else {
    try {
      const DecodedValue value = decodeCdr(*decoding.structure, sample.data.data(), sample.data.size());
      std::cout << toYaml(value, YamlOptions{options.full});
    } catch (const CdrDecodeError& e) {
      std::cerr << "uampc topic echo: a sample of " << sample.data.size() << " bytes cannot be decoded: " << e.what()
                << "\n";
      std::cout << "<" << sample.data.size() << " bytes, not decoded>\n";
    }
  }
  std::cout << "---" << std::endl;
}

int echo(TopicDiscovery& discovery, const DiscoveredTopic& topic, const TopicOptions& options) {
  const Decoding decoding = decodingOf(topic.writers.front().type);
  if (!decoding.structure) {
    std::cerr << "uampc topic echo: type " << shownTypeName(topic.writers.front().type) << " is not known ("
              << decoding.why_not << "): printing each sample's size only\n";
  }
  SampleQueue queue;
  RawSubscription subscription(
      discovery.participant(), topic,
      [&queue](SerializedMessage&& sample, const SampleTimes&) { queue.push(std::move(sample)); });
  int printed = 0;
  while (!stopRequested()) {
    for (const SerializedMessage& sample : queue.takeAll(std::chrono::milliseconds(100))) {
      printSample(sample, decoding, options);
      if (options.count > 0 && ++printed >= options.count) return 0;
    }
  }
  return 0;
}

// hz and bw: figures over the window, reported every second and once more at Ctrl-C.
int measure(TopicDiscovery& discovery, const DiscoveredTopic& topic, const TopicOptions& options) {
  const bool hz = options.action == TopicAction::kHz;
  const int window = options.window > 0 ? options.window : hz ? kDefaultHzWindow : kDefaultBwWindow;
  TopicStatistics statistics(static_cast<std::size_t>(window));
  std::mutex mutex;
  const Clock::time_point start = Clock::now();
  RawSubscription subscription(
      discovery.participant(), topic, [&](SerializedMessage&& sample, const SampleTimes& times) {
        std::lock_guard<std::mutex> lock(mutex);
        statistics.add(std::chrono::duration<double>(times.arrived - start).count(), sample.data.size());
      });
  const auto report = [&] { std::cout << (hz ? statistics.hzReport() : statistics.bwReport()) << std::flush; };
  std::size_t reported = 0;
  for (Clock::time_point next = start + kReportPeriod;; next += kReportPeriod) {
    const bool go_on = sleepUntil(next);
    std::lock_guard<std::mutex> lock(mutex);
    if (!go_on) {
      if (statistics.hasRate()) report();
      return 0;
    }
    if (statistics.received() == reported) {
      if (reported > 0) std::cout << "no new messages" << std::endl;
    } else if (statistics.hasRate()) {
      report();
    }
    reported = statistics.received();
  }
}

int oneTopic(const TopicOptions& options, int domain_id) {
  TopicDiscovery discovery(domain_id, checkedSecurityIdentity(options.security_dir, kObserverIdentity));
  const std::optional<DiscoveredTopic> topic =
      waitForWriter(discovery, ddsTopicFromUser(options.topic), options.wait_s);
  if (stopRequested()) return 0;
  if (!topic) return noWriter(discovery, options, domain_id);
  std::set<std::string> types;
  for (const DiscoveredEndpoint& w : topic->writers) types.insert(w.type);
  std::cerr << "uampc topic: " << options.topic << " [" << shownTypeName(topic->writers.front().type) << "], "
            << topic->writers.size() << (topic->writers.size() == 1 ? " writer" : " writers") << " on domain "
            << domain_id << "\n";
  if (types.size() > 1) {
    std::cerr << "uampc topic: the writers of " << options.topic << " use " << types.size()
              << " types; reading the first's\n";
  }
  return options.action == TopicAction::kEcho ? echo(discovery, *topic, options) : measure(discovery, *topic, options);
}

}  // namespace

int topicCommand(const TopicOptions& options) {
  int domain_id = options.domain_id;
  if (domain_id < 0) {
    try {
      domain_id = rosDomainIdFromEnvironment().value_or(0);
    } catch (const std::invalid_argument& e) {
      std::cerr << "uampc topic: " << e.what() << "\n";
      return kBadEnvironment;
    }
  }
  catchStopSignals();
  try {
    return options.action == TopicAction::kList ? list(options, domain_id) : oneTopic(options, domain_id);
  } catch (const std::runtime_error& e) {
    std::cerr << "uampc topic: " << e.what() << "\n";
    return kNoWriter;
  }
}

void addTopicSubcommands(CLI::App& topic, TopicOptions& options,
                         const std::function<void(const std::string&, const std::string&)>& add_synopsis) {
  topic.require_subcommand(1);
  const auto add = [&](const std::string& name, TopicAction action, const std::string& synopsis,
                       const std::string& description) {
    add_synopsis(name, synopsis);
    CLI::App* sub = topic.add_subcommand(name, description);
    sub->callback([&options, action] { options.action = action; });
    if (action != TopicAction::kList) {
      sub->add_option("TOPIC", options.topic, "A ROS topic (/motor/state) or, without a leading '/', a DDS topic.")
          ->required()
          ->type_name("");
    }
    sub->add_option("--domain", options.domain_id, "The DDS domain (default: $ROS_DOMAIN_ID if set, else 0).")
        ->check(CLI::Range(0, kMaxDomainId).description(""))
        ->type_name("N");
    sub->add_option("--wait", options.wait_s,
                    (action == TopicAction::kList ? "How long discovery runs before the list is printed"
                                                  : "How long to wait for a writer of TOPIC") +
                        std::string(" (default ") + secondsText(kDefaultWaitS) + " s).")
        ->check(uampc::command_line::kFinite)
        ->check(CLI::Range(0.0, 3600.0).description(""))
        ->type_name("S");
    sub->add_option("--security", options.security_dir,
                    "Join a secured domain with the observer identity of DIR (uampc security init), which may read "
                    "every topic.")
        ->type_name("DIR");
    return sub;
  };
  CLI::App* list_command =
      add("list", TopicAction::kList, "uampc topic list [--domain N] [--wait S] [-v] [--security DIR]",
          "Every topic on the domain with its type and its number of writers and readers.");
  list_command->add_flag("-v,--verbose", options.verbose,
                         "Also each writer and reader: its participant's name, GUID prefix and vendor, and its QoS.");
  CLI::App* echo_command =
      add("echo", TopicAction::kEcho, "uampc topic echo TOPIC [--domain N] [--wait S] [-n N] [--full] [--security DIR]",
          "Print TOPIC's samples as YAML (types this uampc knows; of others, the size). Ctrl-C stops.");
  echo_command->add_option("-n", options.count, "Stop after N samples.")
      ->check(uampc::command_line::kPositiveCount.description(""))
      ->type_name("N");
  echo_command->add_flag("--full", options.full,
                         "Print byte arrays whole (longer than " + std::to_string(kLongestBytesShown) +
                             " bytes they are shown as <N bytes>).");
  for (const auto& [name, action, what, default_window] :
       {std::tuple{"hz", TopicAction::kHz, "rate (min/max/std dev of the period)", kDefaultHzWindow},
        std::tuple{"bw", TopicAction::kBw, "bandwidth (mean/min/max sample size)", kDefaultBwWindow}}) {
    CLI::App* sub =
        add(name, action,
            std::string("uampc topic ") + name + " TOPIC [--domain N] [--wait S] [--window N] [--security DIR]",
            std::string("Print TOPIC's ") + what + " every second, over the last N samples. Ctrl-C stops.");
    sub->add_option("--window", options.window,
                    "Samples the figures are over (default " + std::to_string(default_window) + ").")
        ->check(uampc::command_line::kPositiveCount.description(""))
        ->type_name("N");
  }
}

void addTopicCommand(CommandSet& commands) {
  auto options = std::make_shared<TopicOptions>();
  CLI::App* sub =
      commands.add("topic", "uampc topic list|echo|hz|bw [TOPIC] [--domain N] ...",
                   "Look at the topics of a running system, from DDS discovery (uampc's and any other vendor's):\n"
                   "list them with their types, writers and readers; echo a topic's samples as YAML; measure its\n"
                   "rate (hz) or bandwidth (bw). uampc topic list|echo|hz|bw --help describes each.");
  addTopicSubcommands(*sub, *options, [&commands](const std::string& name, const std::string& synopsis) {
    commands.addSynopsis(name, synopsis);
  });
  commands.onRun(sub, [options] { return topicCommand(*options); });
}

}  // namespace uampc::app
