#include "context_impl.hpp"

#include <stdexcept>
#include <utility>

#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/serialized_message.hpp"
#include "dds_writer.hpp"

namespace uampc::process {

using namespace eprosima::fastdds::dds;

ContextImpl::ContextImpl(const Scene& scene, const ComponentInstance& instance, const std::string& output_directory,
                         DdsNode& dds, std::function<DdsNode&()> serialized_dds, ProcessState& state)
    : scene_(scene),
      instance_(instance),
      output_directory_(output_directory),
      dds_(dds),
      serialized_dds_(std::move(serialized_dds)),
      state_(state),
      logger_(instance.name, [&state] { return state.now.seconds(); }) {}

void ContextImpl::timer(double period_s, std::function<void()> callback) {
  if (!(period_s > 0)) throw std::invalid_argument(instance_.name + ": timer period must be positive");
  Time period = Time::fromSeconds(period_s);
  if (state_.lockstep && period < state_.step) {
    logger_.warn("timer period ", period_s, " s is shorter than the lockstep step ", state_.step.seconds(),
                 " s; it fires once per step");
    period = state_.step;
  }
  state_.timers.push_back({instance_.name, period, Time{-1}, std::move(callback)});
}

double ContextImpl::paramDouble(const std::string& n) const {
  const ParameterValue& v = param(n);
  if (auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return std::get<double>(v);
}

std::string ContextImpl::topicOf(const std::string& port) const {
  auto it = instance_.topics.find(port);
  if (it == instance_.topics.end()) {
    throw std::logic_error(instance_.name + ": no port '" + port + "' (not declared in describe())");
  }
  return it->second;
}

std::vector<std::string> ContextImpl::unopenedPorts() const {
  std::vector<std::string> unopened;
  for (const PortSpec& spec : instance_.ports) {
    if (!opened_ports_.count(spec.name)) unopened.push_back(spec.name);
  }
  return unopened;
}

std::shared_ptr<detail::Writer> ContextImpl::makeWriter(const std::string& port, const char* type_name,
                                                        detail::TypeSupportFactory type_support) {
  const PortSpec& spec = checkPort(port, PortDirection::kOutput, type_name);
  return openWriter(port, dds_, type_support, spec);
}

void ContextImpl::addReader(const std::string& port, const char* type_name, detail::TypeSupportFactory type_support,
                            std::function<void(const void*)> callback) {
  const PortSpec& spec = checkPort(port, PortDirection::kInput, type_name);
  if (spec.serialized) {
    throw std::logic_error(instance_.name + ": port '" + port + "' was decided by the scene: open it with "
                           "subscribeSerialized");
  }
  openReader(port, dds_, type_support, spec,
             [callback = std::move(callback)](const void* sample, Time) { callback(sample); });
}

std::shared_ptr<detail::Writer> ContextImpl::makeSerializedWriter(const std::string& port) {
  const PortSpec& spec = checkPort(port, PortDirection::kOutput, nullptr);
  return openWriter(port, serialized_dds_(), serializedTypeSupport(spec), spec);
}

void ContextImpl::addSerializedReader(const std::string& port,
                                      std::function<void(const SerializedMessage&, Time)> callback) {
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

const ParameterValue& ContextImpl::param(const std::string& n) const {
  auto it = instance_.params.find(n);
  if (it == instance_.params.end()) {
    throw std::logic_error(instance_.name + ": no parameter '" + n + "' (not declared in describe())");
  }
  return it->second;
}

std::shared_ptr<detail::Writer> ContextImpl::openWriter(const std::string& port, DdsNode& node,
                                                        const TypeSupportMaker& type_support, const PortSpec& spec) {
  opened_ports_.insert(port);
  const std::string topic = topicOf(port);
  auto writer = std::make_shared<DdsWriter>(node, node.createWriter(topic, spec.type_name, type_support, spec.qos),
                                            topic, spec.qos, state_);
  state_.writers.push_back(writer);
  return writer;
}

void ContextImpl::openReader(const std::string& port, DdsNode& node, const TypeSupportMaker& type_support,
                             const PortSpec& spec, std::function<void(const void*, Time)> callback) {
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

SharedReader* ContextImpl::newDdsReader(DdsNode& node, const std::string& topic, const TypeSupportMaker& type_support,
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

SharedReader* ContextImpl::typedReader(const std::string& topic, const TypeSupportMaker& type_support,
                                       const PortSpec& spec) {
  SharedReader*& reader = state_.typed_readers[{topic, spec.qos}];
  if (!reader) reader = newDdsReader(dds_, topic, type_support, spec);
  return reader;
}

TypeSupportMaker ContextImpl::serializedTypeSupport(const PortSpec& spec) {
  return [name = ddsTypeName(spec.type_name)] { return SerializedTypeSupport::forDdsType(name); };
}

const PortSpec& ContextImpl::checkPort(const std::string& port, PortDirection direction, const char* type_name) const {
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

}  // namespace uampc::process
