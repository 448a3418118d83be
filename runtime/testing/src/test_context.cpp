#include "uampc/runtime/testing/test_context.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "fastdds/rtps/common/SerializedPayload.h"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/parameter_text.hpp"

namespace uampc::testing {

using eprosima::fastdds::dds::TopicDataType;
using eprosima::fastrtps::rtps::SerializedPayload_t;

// Keeps each sample as its serialised bytes: the port's type is known here only by its type
// support, and the test names the C++ type when it reads the samples back.
class TestContext::CapturingWriter : public detail::Writer {
 public:
  CapturingWriter(std::string port, std::string type_name, std::unique_ptr<TopicDataType> type_support,
                  QosPreset qos, const bool& started)
      : port_(std::move(port)), type_name_(std::move(type_name)), type_(std::move(type_support)), qos_(qos),
        started_(started) {}

  void write(const void* sample) override {
    if (!started_ && qos_ != QosPreset::kLatched) {
      // As the runtime refuses it in lockstep: readers in other processes might miss the sample.
      throw std::logic_error("publishing on " + port_ +
                             " before the run started; publish from a timer or a "
                             "callback, or declare the port latched");
    }
    auto* data = const_cast<void*>(sample);  // serialize() takes void* but does not modify it
    auto payload = std::make_unique<SerializedPayload_t>(type_->getSerializedSizeProvider(data)());
    if (!type_->serialize(data, payload.get())) throw std::runtime_error("cannot serialise a sample on " + port_);
    samples_.push_back(std::move(payload));
  }

  void read(std::size_t index, void* sample) const {
    SerializedPayload_t copy;
    copy.copy(samples_.at(index).get(), false);
    if (!type_->deserialize(&copy, sample)) throw std::runtime_error("cannot read back a sample of " + port_);
  }

  // The sample as it travels, whichever way the port was opened.
  SerializedMessage bytes(std::size_t index) const {
    const SerializedPayload_t& payload = *samples_.at(index);
    return {std::vector<std::uint8_t>(payload.data, payload.data + payload.length)};
  }

  const std::string& typeName() const { return type_name_; }
  std::size_t size() const { return samples_.size(); }

 private:
  std::string port_;
  std::string type_name_;
  std::unique_ptr<TopicDataType> type_;
  QosPreset qos_;
  const bool& started_;
  std::vector<std::unique_ptr<SerializedPayload_t>> samples_;
};

namespace {

std::string parameterError(const std::string& type, const std::string& name, const std::string& problem) {
  return type + ": parameter '" + name + "': " + problem;
}

}  // namespace

TestContext::TestContext(const std::string& type, const std::map<std::string, std::string>& params, TestOptions options)
    : options_(std::move(options)), logger_(options_.name, [this] { return now_.seconds(); }) {
  library_ = catalog_.find(type);
  if (!library_) throw std::invalid_argument("no component library for type '" + type + "'");
  for (const auto& [name, text] : params) {
    const ParameterSpec* spec = library_->spec().findParameter(name);
    if (!spec) throw std::invalid_argument(parameterError(type, name, "not declared in describe()"));
    try {
      params_[name] = parseParameterValue(*spec, text);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(type + ": " + e.what());
    }
  }
  for (const ParameterSpec& spec : library_->spec().parameters()) {
    if (params_.count(spec.name)) continue;
    if (spec.required()) throw std::invalid_argument(parameterError(type, spec.name, "required, not given"));
    params_[spec.name] = *spec.default_value;
  }
  ports_ = library_->spec().ports();
  if (const ScenePortResolver& resolve = library_->spec().scenePortResolver()) {
    std::map<std::string, const PortSpec*> written, read;
    for (const PortSpec& output : options_.scene_outputs) written.emplace(output.default_topic, &output);
    for (PortSpec& port : resolve({params_, written, read})) {
      port.default_topic = port.name;
      ports_.push_back(std::move(port));
    }
  }
  component_ = library_->create(*this);
  started_ = true;
}

TestContext::~TestContext() {
  // The component first: it holds publishers and callbacks that point into this context.
  component_.reset();
}

void TestContext::advanceTo(Time t) {
  if (t < now_) throw std::invalid_argument("advanceTo: time may not go back");
  for (;;) {
    Timer* due = nullptr;
    for (Timer& timer : timers_) {
      if (timer.next <= t && (!due || timer.next < due->next)) due = &timer;
    }
    if (!due) break;
    now_ = due->next;
    due->next = due->next + due->period;
    due->callback();
  }
  now_ = t;
}

void TestContext::timer(double period_s, std::function<void()> callback) {
  if (!(period_s > 0)) throw std::invalid_argument(options_.name + ": timer period must be positive");
  timers_.push_back({Time::fromSeconds(period_s), now_, std::move(callback)});
}

const ParameterValue& TestContext::param(const std::string& name) const {
  auto it = params_.find(name);
  if (it == params_.end()) {
    throw std::logic_error(options_.name + ": no parameter '" + name + "' (not declared in describe())");
  }
  return it->second;
}

bool TestContext::paramBool(const std::string& name) const { return std::get<bool>(param(name)); }
std::int64_t TestContext::paramInt(const std::string& name) const { return std::get<std::int64_t>(param(name)); }
double TestContext::paramDouble(const std::string& name) const {
  const ParameterValue& v = param(name);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return std::get<double>(v);
}
std::string TestContext::paramString(const std::string& name) const { return std::get<std::string>(param(name)); }
std::vector<double> TestContext::paramDoubleList(const std::string& name) const {
  return std::get<std::vector<double>>(param(name));
}

std::vector<std::string> TestContext::paramStringList(const std::string& name) const {
  return std::get<std::vector<std::string>>(param(name));
}

const PortSpec* TestContext::findPort(const std::string& port) const {
  for (const PortSpec& p : ports_) {
    if (p.name == port) return &p;
  }
  return nullptr;
}

std::string TestContext::topicOf(const std::string& port) const {
  const PortSpec* spec = findPort(port);
  if (!spec) throw std::logic_error(options_.name + ": no port '" + port + "' (not declared in describe())");
  return spec->default_topic;
}

const PortSpec& TestContext::checkPort(const std::string& port, PortDirection direction, const char* type_name) const {
  const PortSpec* spec = findPort(port);
  if (!spec) throw std::logic_error(options_.name + ": no port '" + port + "' (not declared in describe())");
  if (spec->direction != direction) {
    throw std::logic_error(options_.name + ": port '" + port + "' is declared as an " +
                           (spec->direction == PortDirection::kInput ? "input" : "output"));
  }
  if (type_name && spec->type_name != type_name) {
    throw std::logic_error(options_.name + ": port '" + port + "' is declared with type " + spec->type_name + ", not " +
                           type_name);
  }
  return *spec;
}

std::shared_ptr<detail::Writer> TestContext::makeWriter(const std::string& port, const char* type_name,
                                                        detail::TypeSupportFactory type_support) {
  const PortSpec& spec = checkPort(port, PortDirection::kOutput, type_name);
  auto& writer = writers_[port];
  if (!writer) {
    writer = std::make_shared<CapturingWriter>(port, type_name, std::unique_ptr<TopicDataType>(type_support()), spec.qos,
                                               started_);
  }
  return writer;
}

std::shared_ptr<detail::Writer> TestContext::makeSerializedWriter(const std::string& port) {
  const PortSpec& spec = checkPort(port, PortDirection::kOutput, nullptr);
  auto& writer = writers_[port];
  if (!writer) {
    writer = std::make_shared<CapturingWriter>(
        port, spec.type_name, std::make_unique<SerializedTypeSupport>(ddsTypeName(spec.type_name)), spec.qos, started_);
  }
  return writer;
}

void TestContext::addSerializedReader(const std::string& port,
                                      std::function<void(const SerializedMessage&, Time)> callback) {
  checkPort(port, PortDirection::kInput, nullptr);
  serialized_readers_[port] = std::move(callback);
}

void TestContext::injectSerialized(const std::string& port, const SerializedMessage& sample, Time published) {
  checkPort(port, PortDirection::kInput, nullptr);
  auto it = serialized_readers_.find(port);
  if (it == serialized_readers_.end()) {
    throw std::logic_error(options_.name + ": nothing subscribed serialized to port '" + port + "'");
  }
  it->second(sample, published);
}

std::vector<SerializedMessage> TestContext::publishedSerialized(const std::string& port) const {
  checkPort(port, PortDirection::kOutput, nullptr);
  std::vector<SerializedMessage> samples;
  auto it = writers_.find(port);
  if (it == writers_.end()) return samples;
  for (std::size_t i = 0; i < it->second->size(); ++i) samples.push_back(it->second->bytes(i));
  return samples;
}

void TestContext::addReader(const std::string& port, const char* type_name, detail::TypeSupportFactory,
                            std::function<void(const void*)> callback) {
  checkPort(port, PortDirection::kInput, type_name);
  readers_[port] = std::move(callback);
}

void TestContext::deliver(const std::string& port, const char* type_name, const void* sample) {
  checkPort(port, PortDirection::kInput, type_name);
  auto it = readers_.find(port);
  if (it == readers_.end()) throw std::logic_error(options_.name + ": nothing subscribed to port '" + port + "'");
  it->second(sample);
}

std::size_t TestContext::publishedCount(const std::string& port, const char* type_name) const {
  checkPort(port, PortDirection::kOutput, type_name);
  auto it = writers_.find(port);
  return it == writers_.end() ? 0 : it->second->size();
}

void TestContext::readPublished(const std::string& port, std::size_t index, void* sample) const {
  writers_.at(port)->read(index, sample);
}

}  // namespace uampc::testing
