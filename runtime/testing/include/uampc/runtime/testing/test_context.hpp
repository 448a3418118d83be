// A component in-process, without DDS, for tests: Cyber RT's "Initialize(config), Process(message),
// look at what it wrote", for uampc components.
//
//   testing::TestContext ctx("motor_bridge", {{"encoder_rate", "100"}});
//   ctx.inject<msg::MotorCommand>("command", command);
//   ctx.advanceTo(Time::fromSeconds(0.1));   // fires the timers due, in time order
//   auto states = ctx.published<sensor_msgs::msg::JointState>("state");
//
// The component is built from its plugin library (libuampc_<type>.so), found as the uampc command
// finds it (UAMPC_COMPONENT_PATH, then lib/uampc/components beside the binary's folder: a test in
// build/tests finds build/lib/uampc/components), so the test runs the very code a scene loads.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/runtime/component.hpp"
#include "uampc/runtime/component_library.hpp"

namespace uampc::testing {

struct TestOptions {
  std::string name = "under_test";  // the instance name
  std::uint64_t seed = 1;
  std::string output_directory;  // empty: none, as without uampc launch --out
  Time step = Time{5'000'000};   // what Context::step() says (the tests step the clock by hand)
  // What the rest of the scene writes (default_topic, type_name, qos of each output), for a
  // component that decides its ports from the scene (ComponentSpec::scenePorts).
  std::vector<PortSpec> scene_outputs;
};

class TestContext : public Context {
 public:
  // Loads the type, fills the parameters not given with describe()'s defaults, checks the given
  // ones (declared, type, bounds, choices; values as YAML scalars or flow lists, as in a scene),
  // and constructs the component at time 0. Throws std::invalid_argument naming a bad parameter.
  TestContext(const std::string& type, const std::map<std::string, std::string>& params = {}, TestOptions options = {});
  ~TestContext() override;

  Component& component() { return *component_; }
  const ComponentSpec& spec() const { return library_->spec(); }

  // Delivers a sample on an input port, as the runtime does: the subscribed callback runs now.
  template <typename Message>
  void inject(const std::string& port, const Message& sample) {
    deliver(port, MessageType<Message>::kRosName, &sample);
  }

  // Every sample written on an output port so far, oldest first (copied through the type's CDR
  // serialisation, as they would travel).
  template <typename Message>
  std::vector<Message> published(const std::string& port) const {
    std::vector<Message> samples(publishedCount(port, MessageType<Message>::kRosName));
    for (std::size_t i = 0; i < samples.size(); ++i) readPublished(port, i, &samples[i]);
    return samples;
  }
  std::size_t publishedCount(const std::string& port) const { return publishedCount(port, nullptr); }

  // The same for ports opened serialized (Context::subscribeSerialized, serializedPublisher).
  void injectSerialized(const std::string& port, const SerializedMessage& sample, Time published);
  std::vector<SerializedMessage> publishedSerialized(const std::string& port) const;

  // Moves the clock to t, firing every timer due on the way at its own time, earliest first
  // (timers due at the same time in the order they were created). t may not be in the past.
  void advanceTo(Time t);
  void advanceBy(double seconds) { advanceTo(now_ + Time::fromSeconds(seconds)); }
  // The end of the run: Component::shutdown().
  void shutdown() { component_->shutdown(); }

  // Context
  const std::string& name() const override { return options_.name; }
  const Logger& log() const override { return logger_; }
  Time now() const override { return now_; }
  std::uint64_t seed() const override { return options_.seed; }
  const std::string& outputDirectory() const override { return options_.output_directory; }
  bool lockstep() const override { return true; }
  Time step() const override { return options_.step; }
  void timer(double period_s, std::function<void()> callback) override;
  bool paramBool(const std::string& name) const override;
  std::int64_t paramInt(const std::string& name) const override;
  double paramDouble(const std::string& name) const override;
  std::string paramString(const std::string& name) const override;
  std::vector<double> paramDoubleList(const std::string& name) const override;
  std::vector<std::string> paramStringList(const std::string& name) const override;
  std::string topicOf(const std::string& port) const override;
  const std::vector<PortSpec>& ports() const override { return ports_; }

 protected:
  std::shared_ptr<detail::Writer> makeWriter(const std::string& port, const char* type_name,
                                             detail::TypeSupportFactory type_support) override;
  void addReader(const std::string& port, const char* type_name, detail::TypeSupportFactory type_support,
                 std::function<void(const void*)> callback) override;
  std::shared_ptr<detail::Writer> makeSerializedWriter(const std::string& port) override;
  void addSerializedReader(const std::string& port,
                           std::function<void(const SerializedMessage&, Time)> callback) override;

 private:
  class CapturingWriter;
  struct Timer {
    Time period;
    Time next;
    std::function<void()> callback;
  };

  const PortSpec* findPort(const std::string& port) const;
  const PortSpec& checkPort(const std::string& port, PortDirection direction, const char* type_name) const;
  const ParameterValue& param(const std::string& name) const;
  void deliver(const std::string& port, const char* type_name, const void* sample);
  std::size_t publishedCount(const std::string& port, const char* type_name) const;
  void readPublished(const std::string& port, std::size_t index, void* sample) const;

  TestOptions options_;
  ComponentCatalog catalog_;
  const ComponentLibrary* library_ = nullptr;
  std::map<std::string, ParameterValue> params_;
  std::vector<PortSpec> ports_;  // declared, then decided from options_.scene_outputs
  Logger logger_;
  Time now_{0};
  bool started_ = false;  // false while the component is being constructed
  std::vector<Timer> timers_;
  std::map<std::string, std::function<void(const void*)>> readers_;  // by port
  std::map<std::string, std::shared_ptr<CapturingWriter>> writers_;  // by port
  std::map<std::string, std::function<void(const SerializedMessage&, Time)>> serialized_readers_;  // by port
  std::unique_ptr<Component> component_;
};

}  // namespace uampc::testing
