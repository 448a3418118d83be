#include "uampc/runtime/process_group.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "uampc/msgs/rosgraph_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/wall_clock.hpp"
#include "lockstep_clock.hpp"
#include "wakeup.hpp"

namespace uampc {

using namespace eprosima::fastdds::dds;
using SteadyClock = std::chrono::steady_clock;

namespace {

// A sample taken from a reader, owned until it is delivered.
struct Sample {
  std::shared_ptr<void> data;
  Time source_time;
};

struct ReaderPort;

// A DDS reader and the input ports it serves. Typed inputs of one process on one topic and QoS
// share one (Scene::readersOf): every DDS delivery costs the same whatever the sample's size (on
// Debian's Fast DDS build, several system calls of its debug checks), and the default loop's
// /motor/state alone has five readers in one process.
struct SharedReader {
  std::string topic;
  DdsNode* node = nullptr;  // the participant the reader belongs to
  DataReader* reader = nullptr;
  TypeSupport type;
  std::vector<ReaderPort*> ports;
  std::unique_ptr<ReaderActivity> activity;  // its listener; outlives the reader (deleted first)

  // Takes every sample the reader holds into each port's inbox, in arrival order.
  void poll();
};

// An input port of a component: its own view of its shared reader's samples.
struct ReaderPort {
  std::string component;
  std::string port;
  std::string topic;
  SharedReader* shared = nullptr;
  std::function<void(const void*, Time source_time)> callback;
  std::deque<Sample> inbox;     // taken from the DDS reader, not yet looked at by this port
  std::deque<Sample> deferred;  // lockstep: taken early, belongs to a later step
  std::uint64_t delivered = 0;  // samples handed to the callback so far

  // The samples its shared reader has taken for it so far, in arrival order.
  void drainInbox(std::deque<Sample>& out) {
    for (auto& s : inbox) out.push_back(std::move(s));
    inbox.clear();
  }
  // The same after taking what arrived since (a take costs DDS calls even on an empty reader).
  void takeAll(std::deque<Sample>& out) {
    shared->poll();
    drainInbox(out);
  }
};

void SharedReader::poll() {
  if (!activity->takeMark()) return;  // nothing arrived since the last poll
  for (;;) {
    std::shared_ptr<void> data(type->createData(), [t = type](void* p) { t->deleteData(p); });
    SampleInfo info;
    if (reader->take_next_sample(data.get(), &info) != ReturnCode_t::RETCODE_OK) return;
    if (!info.valid_data) continue;
    const auto& ts = info.source_timestamp;
    const Sample sample{std::move(data), Time{static_cast<std::int64_t>(ts.seconds()) * 1000000000 + ts.nanosec()}};
    for (ReaderPort* port : ports) port->inbox.push_back(sample);  // the data is shared, read-only
  }
}

// A reader with one port of its own: the clock's protocol topics.
struct ProtocolReader {
  SharedReader shared;
  ReaderPort port;
  ProtocolReader(DdsNode& node, const std::string& topic, const char* type_name, TypeSupportMaker type_support,
                 Wakeup* wakeup) {
    shared.topic = port.topic = topic;
    shared.node = &node;
    shared.type = TypeSupport(type_support());
    shared.activity = std::make_unique<ReaderActivity>(*wakeup);
    shared.reader = node.createReader(topic, type_name, type_support, QosPreset::kControl, shared.activity.get());
    shared.ports.push_back(&port);
    port.shared = &shared;
  }
  ~ProtocolReader() { shared.node->deleteReader(shared.reader); }
  void takeAll(std::deque<Sample>& out) { port.takeAll(out); }
};

struct TimerEntry {
  std::string component;
  Time period;
  Time next;
  std::function<void()> callback;
};

class DdsWriter;

// State shared by the contexts of one process: the clock, the list of ports and timers, and why
// the process failed.
struct ProcessState {
  bool lockstep = false;
  bool started = false;  // false while components are being constructed
  Time now;
  Time step;
  Wakeup wakeup;
  std::vector<std::unique_ptr<ReaderPort>> readers;  // in the order components opened them
  std::vector<std::unique_ptr<SharedReader>> dds_readers;
  std::map<std::pair<std::string, QosPreset>, SharedReader*> typed_readers;  // by topic and QoS
  std::vector<std::shared_ptr<DdsWriter>> writers;  // the components' outputs, in the order opened
  std::vector<TimerEntry> timers;
  std::string failure;  // why the process failed, told in its acknowledgements; empty: it has not
};

class DdsWriter : public detail::Writer {
 public:
  DdsWriter(DdsNode& node, DataWriter* writer, std::string topic, QosPreset qos, const ProcessState& state)
      : node_(node), writer_(writer), topic_(std::move(topic)), qos_(qos), state_(state) {}
  ~DdsWriter() override { node_.deleteWriter(writer_); }
  void write(const void* sample) override {
    if (state_.lockstep && !state_.started && qos_ != QosPreset::kLatched) {
      // Before the run starts, readers in other processes may not be matched yet and the sample
      // would be lost. Latched samples are kept for them, so those may be written.
      throw std::logic_error("publishing on " + topic_ +
                             " before the run started; publish from a timer or a "
                             "callback, or declare the port latched");
    }
    auto* data = const_cast<void*>(sample);  // Fast DDS takes void* but does not modify it
    ReturnCode_t rc;
    if (state_.lockstep) {
      // The source timestamp carries the step that produced the sample; readers defer samples
      // of the current step to the next one, whichever process they come from (see deliverInputs).
      eprosima::fastrtps::Time_t stamp(static_cast<std::int32_t>(state_.now.ns / 1000000000),
                                       static_cast<std::uint32_t>(state_.now.ns % 1000000000));
      rc = writer_->write_w_timestamp(data, HANDLE_NIL, stamp);
    } else {
      rc = writer_->write(data) ? ReturnCode_t::RETCODE_OK : ReturnCode_t::RETCODE_ERROR;
    }
    if (rc != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("publishing on " + topic_ + " failed (DDS return code " + std::to_string(rc()) + ")");
    }
    ++written_;
  }
  DataWriter* dds() const { return writer_; }
  const std::string& topic() const { return topic_; }
  std::uint64_t written() const { return written_; }

 private:
  DdsNode& node_;
  DataWriter* writer_;
  std::string topic_;
  QosPreset qos_;
  const ProcessState& state_;
  std::uint64_t written_ = 0;
};

class ContextImpl : public Context {
 public:
  // serialized_dds: the participant of the process's serialized ports, made on first use.
  ContextImpl(const Scene& scene, const ComponentInstance& instance, const std::string& output_directory, DdsNode& dds,
              std::function<DdsNode&()> serialized_dds, ProcessState& state)
      : scene_(scene),
        instance_(instance),
        output_directory_(output_directory),
        dds_(dds),
        serialized_dds_(std::move(serialized_dds)),
        state_(state),
        logger_(instance.name, [&state] { return state.now.seconds(); }) {}

  const std::string& name() const override { return instance_.name; }
  const Logger& log() const override { return logger_; }
  Time now() const override { return state_.now; }
  std::uint64_t seed() const override { return scene_.seed; }
  const std::string& outputDirectory() const override { return output_directory_; }
  bool lockstep() const override { return state_.lockstep; }
  Time step() const override { return state_.lockstep ? state_.step : Time{0}; }

  void timer(double period_s, std::function<void()> callback) override {
    if (!(period_s > 0)) throw std::invalid_argument(instance_.name + ": timer period must be positive");
    Time period = Time::fromSeconds(period_s);
    if (state_.lockstep && period < state_.step) {
      logger_.warn("timer period ", period_s, " s is shorter than the lockstep step ", state_.step.seconds(),
                   " s; it fires once per step");
      period = state_.step;
    }
    state_.timers.push_back({instance_.name, period, Time{-1}, std::move(callback)});
  }

  bool paramBool(const std::string& n) const override { return std::get<bool>(param(n)); }
  std::int64_t paramInt(const std::string& n) const override { return std::get<std::int64_t>(param(n)); }
  double paramDouble(const std::string& n) const override {
    const ParameterValue& v = param(n);
    if (auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
    return std::get<double>(v);
  }
  std::string paramString(const std::string& n) const override { return std::get<std::string>(param(n)); }
  std::vector<double> paramDoubleList(const std::string& n) const override {
    return std::get<std::vector<double>>(param(n));
  }
  std::vector<std::string> paramStringList(const std::string& n) const override {
    return std::get<std::vector<std::string>>(param(n));
  }
  const std::vector<PortSpec>& ports() const override { return instance_.ports; }
  std::string topicOf(const std::string& port) const override {
    auto it = instance_.topics.find(port);
    if (it == instance_.topics.end()) {
      throw std::logic_error(instance_.name + ": no port '" + port + "' (not declared in describe())");
    }
    return it->second;
  }

  // Declared ports the component opened neither a publisher nor a subscription on. The start of a
  // run waits until every declared port is matched, so such a port would stall it.
  std::vector<std::string> unopenedPorts() const {
    std::vector<std::string> unopened;
    for (const PortSpec& spec : instance_.ports) {
      if (!opened_ports_.count(spec.name)) unopened.push_back(spec.name);
    }
    return unopened;
  }

 protected:
  std::shared_ptr<detail::Writer> makeWriter(const std::string& port, const char* type_name,
                                             detail::TypeSupportFactory type_support) override {
    const PortSpec& spec = checkPort(port, PortDirection::kOutput, type_name);
    return openWriter(port, dds_, type_support, spec);
  }

  void addReader(const std::string& port, const char* type_name, detail::TypeSupportFactory type_support,
                 std::function<void(const void*)> callback) override {
    const PortSpec& spec = checkPort(port, PortDirection::kInput, type_name);
    if (spec.serialized) {
      throw std::logic_error(instance_.name + ": port '" + port + "' was decided by the scene: open it with "
                             "subscribeSerialized");
    }
    openReader(port, dds_, type_support, spec,
               [callback = std::move(callback)](const void* sample, Time) { callback(sample); });
  }

  // Serialized ports live on a participant of their own: one participant registers one type
  // support per type name, and the process's typed ports of the same type have theirs.
  std::shared_ptr<detail::Writer> makeSerializedWriter(const std::string& port) override {
    const PortSpec& spec = checkPort(port, PortDirection::kOutput, nullptr);
    return openWriter(port, serialized_dds_(), serializedTypeSupport(spec), spec);
  }

  void addSerializedReader(const std::string& port,
                           std::function<void(const SerializedMessage&, Time)> callback) override {
    const PortSpec& spec = checkPort(port, PortDirection::kInput, nullptr);
    if (!spec.serialized) {
      throw std::logic_error(instance_.name + ": port '" + port + "' is declared in describe(): subscribe to it typed "
                             "(serialized inputs are those the scene decides, ComponentSpec::scenePorts)");
    }
    openReader(port, serialized_dds_(), serializedTypeSupport(spec), spec,
               [callback = std::move(callback)](const void* sample, Time published) {
                 callback(*static_cast<const SerializedMessage*>(sample), published);
               });
  }

 private:
  const ParameterValue& param(const std::string& n) const {
    auto it = instance_.params.find(n);
    if (it == instance_.params.end()) {
      throw std::logic_error(instance_.name + ": no parameter '" + n + "' (not declared in describe())");
    }
    return it->second;
  }
  std::shared_ptr<detail::Writer> openWriter(const std::string& port, DdsNode& node,
                                             const TypeSupportMaker& type_support, const PortSpec& spec) {
    opened_ports_.insert(port);
    const std::string topic = topicOf(port);
    auto writer = std::make_shared<DdsWriter>(node, node.createWriter(topic, spec.type_name, type_support, spec.qos),
                                              topic, spec.qos, state_);
    state_.writers.push_back(writer);
    return writer;
  }

  void openReader(const std::string& port, DdsNode& node, const TypeSupportMaker& type_support, const PortSpec& spec,
                  std::function<void(const void*, Time)> callback) {
    opened_ports_.insert(port);
    auto r = std::make_unique<ReaderPort>();
    r->component = instance_.name;
    r->port = port;
    r->topic = topicOf(port);
    r->callback = std::move(callback);
    r->shared = spec.serialized ? newDdsReader(node, r->topic, type_support, spec) : typedReader(r->topic, type_support, spec);
    r->shared->ports.push_back(r.get());
    state_.readers.push_back(std::move(r));
  }

  SharedReader* newDdsReader(DdsNode& node, const std::string& topic, const TypeSupportMaker& type_support,
                             const PortSpec& spec) {
    auto reader = std::make_unique<SharedReader>();
    reader->topic = topic;
    reader->node = &node;
    reader->type = TypeSupport(type_support());
    reader->activity = std::make_unique<ReaderActivity>(state_.wakeup);
    reader->reader = node.createReader(topic, spec.type_name, type_support, spec.qos, reader->activity.get());
    state_.dds_readers.push_back(std::move(reader));
    return state_.dds_readers.back().get();
  }

  // The process's typed reader of the topic with the port's QoS, made on first use.
  SharedReader* typedReader(const std::string& topic, const TypeSupportMaker& type_support, const PortSpec& spec) {
    SharedReader*& reader = state_.typed_readers[{topic, spec.qos}];
    if (!reader) reader = newDdsReader(dds_, topic, type_support, spec);
    return reader;
  }

  static TypeSupportMaker serializedTypeSupport(const PortSpec& spec) {
    return [name = ddsTypeName(spec.type_name)] { return SerializedTypeSupport::forDdsType(name); };
  }

  const PortSpec& checkPort(const std::string& port, PortDirection direction, const char* type_name) const {
    const PortSpec* spec = instance_.findPort(port);
    if (!spec) throw std::logic_error(instance_.name + ": no port '" + port + "' (not declared in describe())");
    if (spec->direction != direction) {
      throw std::logic_error(instance_.name + ": port '" + port + "' is declared as an " +
                             (spec->direction == PortDirection::kInput ? "input" : "output"));
    }
    if (type_name && spec->type_name != type_name) {
      throw std::logic_error(instance_.name + ": port '" + port + "' is declared with type " + spec->type_name +
                             ", not " + type_name);
    }
    return *spec;
  }

  const Scene& scene_;
  const ComponentInstance& instance_;
  std::string output_directory_;
  DdsNode& dds_;
  std::function<DdsNode&()> serialized_dds_;
  ProcessState& state_;
  std::set<std::string> opened_ports_;
  Logger logger_;
};

// Samples written on each topic, by this process or summed over the processes' acknowledgements.
using TopicCounts = std::map<std::string, std::uint64_t>;

// How one step ended for the process.
enum class StepOutcome { kDone, kStopped, kFailed };

int exitCodeOf(StepOutcome outcome) { return outcome == StepOutcome::kFailed ? 1 : 0; }

// The components of one process: constructed in the scene's order, each with its context, and at
// the end each shut down, even after another has failed.
class ComponentGroup {
 public:
  // serialized_dds: the participant of the process's serialized ports, made on first use.
  ComponentGroup(const Scene& scene, const std::string& process, const std::string& output_directory, DdsNode& dds,
                 std::function<DdsNode&()> serialized_dds, ProcessState& state, const Logger& log)
      : scene_(scene),
        process_(process),
        output_directory_(output_directory),
        dds_(dds),
        serialized_dds_(std::move(serialized_dds)),
        state_(state),
        log_(log) {}

  // False (said in the log) when a component could not start or left a declared port unopened.
  bool create() {
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

  // Every component's shutdown, even after one has failed: each writes its own outputs (a
  // recorder's file is whole only once it is closed), and one component's full disk is no reason
  // to lose another's files. False when any failed.
  bool shutDown() {
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

  // The components themselves, before the readers and writers their callbacks use.
  void destroy() { components_.clear(); }

 private:
  bool construct(const ComponentInstance& instance) {
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

  bool hasSerializedPorts() const {
    for (const auto& instance : scene_.components) {
      if (instance.process != process_) continue;
      for (const PortSpec& port : instance.ports)
        if (port.serialized) return true;
    }
    return false;
  }

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
  bool guarded(const std::string& component, const char* what, const std::function<void()>& work) {
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

  // Delivers the samples that arrived, in a fixed order: readers in the order components created
  // them, samples of one reader in arrival order. In lockstep, exactly the samples published in
  // earlier steps are delivered: the reader first waits until it holds as many samples stamped
  // before now as the processes' acknowledgements say were written on its topic (expected), and
  // samples of the current step (source time >= now) wait for the next one. Every hop between
  // components therefore takes exactly one step, in one process or in several, which is what
  // makes runs deterministic.
  bool deliverInputs(const TopicCounts* expected, const std::function<bool()>& give_up) {
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

  // Lockstep: takes samples until the reader holds every sample written before now on its topic.
  bool awaitSamples(ReaderPort& r, std::deque<Sample>& samples, const TopicCounts& expected,
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

  bool fireTimers() {
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

  const Scene& scene_;
  ProcessState& state_;
  const Logger& log_;
};

// The components' ports discovery has not matched yet: each writer's readers and each reader's
// writers as the scene counts them. One line each, empty when all are matched.
std::string unmatchedPorts(const Scene& scene, const ProcessState& state) {
  std::string missing;
  for (const auto& w : state.writers) {
    PublicationMatchedStatus s;
    w->dds()->get_publication_matched_status(s);
    const int want = scene.readersOf(w->topic());
    if (s.current_count < want) {
      missing += "\n  writer on " + w->topic() + ": " + std::to_string(s.current_count) + " of " +
                 std::to_string(want) + " readers";
    }
  }
  for (const auto& r : state.dds_readers) {
    SubscriptionMatchedStatus s;
    r->reader->get_subscription_matched_status(s);
    const int want = scene.writersOf(r->topic);
    if (s.current_count < want) {
      missing += "\n  reader on " + r->topic + ": " + std::to_string(s.current_count) + " of " + std::to_string(want) +
                 " writers";
    }
  }
  return missing;
}

// The lockstep protocol as one process speaks it (docs/dev/time-and-lockstep.md): the launcher's
// ticks on /clock, or this process's own /clock when it steps itself; its acknowledgements of each
// step with the samples it wrote, to the clock and the other processes; its progress, to the
// launcher; the other processes' acknowledgements; and another run on the domain, noticed.
class LockstepProtocol {
 public:
  // Opens the protocol's topics. They are reliable and keep every sample, like the loop's own.
  LockstepProtocol(const Scene& scene, const std::string& process, bool own_clock, DdsNode& dds, ProcessState& state,
                   const Logger& log)
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

  ~LockstepProtocol() {
    clock_reader_.reset();
    if (clock_writer_) dds_.deleteWriter(clock_writer_);
    ack_writer_.reset();
    progress_writer_.reset();
    ack_reader_.reset();
  }

  // Alone in its scene: no other process's acknowledgements to wait for.
  bool alone() const { return !ack_reader_; }

  // The protocol's endpoints discovery has not matched yet, one line each; empty when all are.
  std::string unmatched() const {
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

  // The ready message (step -1), to whoever hears this process's acknowledgements and progress.
  void sayReady() {
    if (ack_writer_) sendAck(-1, Time{0});
    if (progress_writer_) reportProgress(-1, Time{0});
  }

  // The times the launcher's clock has ticked since the last call.
  std::vector<Time> takeTicks() {
    std::deque<Sample> ticks;
    clock_reader_->takeAll(ticks);
    std::vector<Time> times;
    for (const auto& tick : ticks)
      times.push_back(fromMsg(static_cast<const rosgraph_msgs::msg::Clock*>(tick.data.get())->clock()));
    return times;
  }

  // /clock for outside tools, if this process publishes it.
  void publishClock(Time t) {
    if (!clock_writer_) return;
    rosgraph_msgs::msg::Clock tick;
    tick.clock(toMsg(t));
    clock_writer_->write(&tick);
  }

  // The acknowledgement of a step, to the launcher's clock and the other processes.
  void sendAck(std::int64_t step, Time stamp) {
    uampc::msg::StepAck ack = ackOf(step, stamp);
    // Alone under the launcher's clock: what the others would have read (with the clock inside,
    // runOwnClock keeps its counts itself).
    if (!ack_reader_ && !own_clock_) acks_[process_][step] = ack.written();
    ack_writer_->write(&ack);
  }

  // How far a process that steps itself is, to the launcher.
  void reportProgress(std::int64_t step, Time stamp) {
    uampc::msg::StepAck ack = ackOf(step, stamp);
    progress_writer_->write(&ack);
  }

  // Before a failed lockstep process exits (run(), on any failure): its last acknowledgement, which
  // says why, is in its readers' hands. Otherwise the launcher may see the exit first and report
  // only "exited with status 1" (seen in CI). Bounded: a reader that is gone does not keep the
  // process; without acknowledgement writers (a failure before they exist) a no-op.
  void deliverFailure() {
    const eprosima::fastrtps::Duration_t patience(1, 0);
    for (DdsWriter* writer : {ack_writer_.get(), progress_writer_.get()}) {
      if (writer) writer->dds()->wait_for_acknowledgments(patience);
    }
  }

  // The acknowledgements of step `step` from every process, summed into the number of samples
  // written on each topic; false on timeout or stop.
  bool awaitAcks(std::int64_t step, TopicCounts& expected, const std::atomic<bool>& stop) {
    // A little before the clock gives up: the clock then hears from this process which peer it
    // waited for (a stopped process), instead of naming every process as late.
    const auto deadline = SteadyClock::now() + std::chrono::duration<double>(0.9 * scene_.clock.ack_timeout_s);
    for (;;) {
      takeAcks();
      const std::string missing = notAcknowledged(step);
      if (missing.empty()) break;
      if (stop || anotherRunStops()) return false;
      if (SteadyClock::now() > deadline) {
        state_.failure = "acknowledgements of step " + std::to_string(step) + " from process(es) " + missing +
                         " did not arrive within " + std::to_string(0.9 * scene_.clock.ack_timeout_s) + " s";
        log_.error(state_.failure);
        return false;
      }
      state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::milliseconds(10));
    }
    expected = countsOf(step);
    return true;
  }

  // While waiting: another run on the domain is a failure, said once the other run may have noticed.
  bool anotherRunStops() {
    state_.failure = anotherRun();
    if (state_.failure.empty()) return false;
    log_.error(state_.failure);
    stayUntilTheOtherRunNotices();
    return true;
  }

  // The samples this process has written on each topic so far.
  TopicCounts writtenSoFar() const {
    TopicCounts written;
    for (const auto& w : state_.writers) written[w->topic()] += w->written();
    return written;
  }

 private:
  std::unique_ptr<DdsWriter> stepAckWriter(const char* topic) {
    return std::make_unique<DdsWriter>(
        dds_,
        dds_.createWriter(topic, MessageType<uampc::msg::StepAck>::kRosName,
                          &detail::makeTypeSupport<uampc::msg::StepAck>, QosPreset::kControl),
        topic, QosPreset::kControl, state_);
  }

  // The counts an acknowledgement of `step` carries. The ready message (step -1) counts nothing:
  // samples written while the components were constructed (latched ones) carry time 0 and are
  // delivered at step 1, counted by step 0's acknowledgement.
  std::vector<uampc::msg::TopicCount> writtenBy(std::int64_t step) const {
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

  uampc::msg::StepAck ackOf(std::int64_t step, Time stamp) const {
    uampc::msg::StepAck ack;
    ack.process(process_);
    ack.step(step);
    ack.stamp(toMsg(stamp));
    ack.written() = writtenBy(step);
    ack.failed(!state_.failure.empty());
    ack.message(state_.failure);
    return ack;
  }

  // Keeps every acknowledgement that arrived, by process and step.
  void takeAcks() {
    std::deque<Sample> acks;
    if (ack_reader_) ack_reader_->takeAll(acks);
    for (const auto& a : acks) {
      const auto* ack = static_cast<const uampc::msg::StepAck*>(a.data.get());
      acks_[ack->process()][ack->step()] = ack->written();
    }
  }

  // The processes whose acknowledgement of `step` has not arrived, comma-separated. A faster process
  // may already have acknowledged later steps; the counts must be those of exactly this step.
  std::string notAcknowledged(std::int64_t step) const {
    std::string missing;
    for (const auto& p : scene_.processes()) {
      auto it = acks_.find(p);
      if (it == acks_.end() || !it->second.count(step)) missing += (missing.empty() ? "" : ", ") + p;
    }
    return missing;
  }

  // The samples every process wrote by the end of `step`, summed per topic; older steps are
  // forgotten, as they are not needed again.
  TopicCounts countsOf(std::int64_t step) {
    TopicCounts expected;
    for (auto& [process, by_step] : acks_) {
      for (const auto& c : by_step.at(step)) expected[c.topic()] += c.count();
      by_step.erase(by_step.begin(), by_step.find(step));
    }
    return expected;
  }

  // Another lockstep run on this domain, whose ticks would drive this one or whose acknowledgements
  // would mix with its own: a second writer of /clock ever, or more writers of acknowledgements than
  // the scene has processes (the launcher checks its readers the same way).
  std::string anotherRun() const {
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

  const Scene& scene_;
  const std::string& process_;
  const bool own_clock_;
  DdsNode& dds_;
  ProcessState& state_;
  const Logger& log_;
  std::unique_ptr<ProtocolReader> clock_reader_;  // ticks of the launcher's clock
  DataWriter* clock_writer_ = nullptr;            // or this process's own (own_clock_)
  std::unique_ptr<DdsWriter> ack_writer_;         // to the launcher's clock and the other processes
  std::unique_ptr<DdsWriter> progress_writer_;    // to the launcher, when the process steps itself
  std::unique_ptr<ProtocolReader> ack_reader_;
  // Acknowledged sample counts: process -> step -> counts per topic.
  std::map<std::string, std::map<std::int64_t, std::vector<uampc::msg::TopicCount>>> acks_;
};

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
                   " s; still missing:", missing);
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

  // The launcher's clock ticks each step once every process acknowledged the one before.
  int followLauncherClock(const std::atomic<bool>& stop) {
    while (!stop) {
      state_.wakeup.waitUntil(SteadyClock::now() + std::chrono::milliseconds(100));
      if (protocol_->anotherRunStops()) return 1;
      for (const Time t : protocol_->takeTicks()) {
        const StepOutcome outcome = tickedStep(t, stop);
        if (outcome != StepOutcome::kDone) return exitCodeOf(outcome);
      }
      // Data may have arrived for later steps; the tick will come.
    }
    return 0;
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

int runProcessGroup(const Scene& scene, const std::string& process, const std::string& output_directory,
                    const std::atomic<bool>& stop, bool own_clock) {
  try {
    ProcessRunner runner(scene, process, output_directory, own_clock);
    return runner.run(stop);
  } catch (const std::exception& e) {
    Logger(process, {}).error(e.what());
    return 1;
  }
}

}  // namespace uampc
