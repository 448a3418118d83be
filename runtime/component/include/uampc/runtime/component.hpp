// The one header a component includes.
//
// Writing a component takes one class and one registration line:
//
//   class ConstantSpeedController : public uampc::Component {
//    public:
//     static void describe(uampc::ComponentSpec& spec);   // ports and parameters
//     explicit ConstantSpeedController(uampc::Context& ctx); // set up publishers, subscriptions, timers
//   };
//   UAMPC_REGISTER_COMPONENT(ConstantSpeedController, "constant_speed_controller")
//
// The runtime loads the library with dlopen, validates the scene against describe(), builds the
// object with a Context bound to its ports and parameters, and calls it from one thread per process:
// a component never needs a lock. Exceptions thrown from a callback stop the run with the
// component's name and the message (a component reports bad input it cannot handle by throwing).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "uampc/runtime/component_spec.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/message_type.hpp"
#include "uampc/runtime/parameter.hpp"
#include "uampc/runtime/serialized_message.hpp"
#include "uampc/runtime/time.hpp"

namespace uampc {

// Bumped whenever Component, Context or the plugin entry change in a way that breaks libraries
// built against an older runtime. The loader refuses a library built for another version.
// 2: ParameterSpec::rig; 3: ports decided by the scene, serialized ports, string-list parameters;
// 4: ParameterSpec::not_with.
constexpr std::uint32_t kComponentAbiVersion = 4;

namespace detail {
// The runtime's side of a typed port; components use Publisher<T> and Context::subscribe<T>.
class Writer {
 public:
  virtual ~Writer() = default;
  virtual void write(const void* sample) = 0;
};
}  // namespace detail

template <typename Message>
class Publisher {
 public:
  Publisher() = default;
  explicit Publisher(std::shared_ptr<detail::Writer> writer) : writer_(std::move(writer)) {}
  void publish(const Message& message) const {
    if (!writer_) throw std::logic_error("publish() on a Publisher that was never bound to a port");
    writer_->write(&message);
  }
  explicit operator bool() const { return static_cast<bool>(writer_); }

 private:
  std::shared_ptr<detail::Writer> writer_;
};

class Context {
 public:
  virtual ~Context() = default;

  // Instance name from the scene, e.g. "motor".
  virtual const std::string& name() const = 0;
  virtual const Logger& log() const = 0;
  // Current time of the scene's clock: sim time in lockstep mode, wall time in real-time mode.
  virtual Time now() const = 0;
  // The scene's seed; components derive their random streams from it (and their name).
  virtual std::uint64_t seed() const = 0;
  // Output directory of the run (uampc launch --out DIR); empty when none was given.
  virtual const std::string& outputDirectory() const = 0;
  // True in lockstep (deterministic, simulated time) mode.
  virtual bool lockstep() const = 0;
  // Lockstep: the clock's step (a timer never fires more often); real time: 0.
  virtual Time step() const = 0;

  template <typename Message>
  Publisher<Message> publisher(const std::string& port) {
    return Publisher<Message>(
        makeWriter(port, MessageType<Message>::kRosName, &detail::makeTypeSupport<Message>));
  }

  // callback runs on the component's thread for every sample that arrives on the port.
  template <typename Message>
  void subscribe(const std::string& port, std::function<void(const Message&)> callback) {
    addReader(port, MessageType<Message>::kRosName, &detail::makeTypeSupport<Message>,
              [callback = std::move(callback)](const void* sample) {
                callback(*static_cast<const Message*>(sample));
              });
  }

  // Ports of any type, the samples kept as their CDR bytes: how a recorder or a player moves
  // samples without knowing their types (ports decided by the scene, ComponentSpec::scenePorts; a
  // declared port may be opened this way too). `published` is when the writer published the sample
  // (sim time in lockstep, wall time in real time).
  Publisher<SerializedMessage> serializedPublisher(const std::string& port) {
    return Publisher<SerializedMessage>(makeSerializedWriter(port));
  }
  void subscribeSerialized(const std::string& port,
                           std::function<void(const SerializedMessage&, Time published)> callback) {
    addSerializedReader(port, std::move(callback));
  }
  // Every port of this instance: the declared ones, then those the scene decided.
  virtual const std::vector<PortSpec>& ports() const = 0;

  // callback runs every period_s seconds of clock time, first at the start of the run.
  virtual void timer(double period_s, std::function<void()> callback) = 0;

  // Parameter values, already validated against the component's describe().
  virtual bool paramBool(const std::string& name) const = 0;
  virtual std::int64_t paramInt(const std::string& name) const = 0;
  virtual double paramDouble(const std::string& name) const = 0;  // accepts integer values too
  virtual std::string paramString(const std::string& name) const = 0;  // paths come back absolute
  virtual std::vector<double> paramDoubleList(const std::string& name) const = 0;
  virtual std::vector<std::string> paramStringList(const std::string& name) const = 0;

  // The topic a port is bound to after the scene's remapping, e.g. "/motor/state".
  virtual std::string topicOf(const std::string& port) const = 0;

 protected:
  virtual std::shared_ptr<detail::Writer> makeWriter(const std::string& port, const char* type_name,
                                                     detail::TypeSupportFactory type_support) = 0;
  virtual void addReader(const std::string& port, const char* type_name,
                         detail::TypeSupportFactory type_support,
                         std::function<void(const void*)> callback) = 0;
  virtual std::shared_ptr<detail::Writer> makeSerializedWriter(const std::string& port) = 0;
  virtual void addSerializedReader(const std::string& port,
                                   std::function<void(const SerializedMessage&, Time)> callback) = 0;
};

class Component {
 public:
  virtual ~Component() = default;
  // Called once after the last step, before the process exits: write results, close files.
  virtual void shutdown() {}
};

// What a component library exports, through one C symbol (uampc_component_plugin).
struct ComponentPlugin {
  std::uint32_t abi_version;
  const char* type;
  void (*describe)(ComponentSpec& spec);
  Component* (*create)(Context& context);
};

}  // namespace uampc

#define UAMPC_COMPONENT_PLUGIN_SYMBOL "uampc_component_plugin"

// One registration line per component library.
#define UAMPC_REGISTER_COMPONENT(Class, type_name)                                     \
  extern "C" __attribute__((visibility("default"))) const ::uampc::ComponentPlugin*    \
  uampc_component_plugin() {                                                           \
    static const ::uampc::ComponentPlugin plugin{                                      \
        ::uampc::kComponentAbiVersion, type_name,                                      \
        [](::uampc::ComponentSpec& spec) {                                             \
          spec.type = type_name;                                                       \
          Class::describe(spec);                                                       \
        },                                                                             \
        [](::uampc::Context& context) -> ::uampc::Component* { return new Class(context); }}; \
    return &plugin;                                                                    \
  }
