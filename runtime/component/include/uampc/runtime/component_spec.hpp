// What a component type declares about itself: its ports and parameters. The launcher validates a
// scene against these before anything starts, and `uampc components` lists them.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "uampc/runtime/message_type.hpp"
#include "uampc/runtime/parameter.hpp"
#include "uampc/runtime/qos.hpp"

namespace uampc {

enum class PortDirection { kInput, kOutput };

struct PortSpec {
  std::string name;
  PortDirection direction = PortDirection::kInput;
  std::string type_name;      // ROS 2 name, e.g. "sensor_msgs/msg/PointCloud2"
  std::string default_topic;  // ROS 2 topic name, e.g. "/lidar/points"
  QosPreset qos = QosPreset::kControl;
  std::string doc;
  // Decided by the scene (ComponentSpec::scenePorts) and opened serialized. An input opened
  // serialized has a DDS reader of its own; typed inputs of one process on one topic and QoS share
  // one (Scene::readersOf counts them so).
  bool serialized = false;
  // An output for viewers and tools (TF, a map to look at, running metrics): that nobody in the
  // scene reads it is expected, not a mistake worth a warning.
  bool for_viewers = false;
  // An output whose topic must have no other writer in the scene (a motor command, a world, a
  // pose): a second writer on it is a validation error, not a warning. Two controllers on
  // /motor/command would both drive the motor; two worlds on /ground_truth/pose lose the LO.
  bool sole_writer = false;

  PortSpec& forViewers() {
    for_viewers = true;
    return *this;
  }
  PortSpec& soleWriter() {
    sole_writer = true;
    return *this;
  }
};

// What a component that decides its ports from the scene (ComponentSpec::scenePorts) is given.
struct ScenePortRequest {
  const std::map<std::string, ParameterValue>& params;  // the instance's, validated, defaults filled in
  // Every topic the scene's other components write (declared outputs and the outputs other
  // components decided from the scene), with the port that writes it first.
  const std::map<std::string, const PortSpec*>& written;
  // Every topic they read, with the first port reading it: on a rig, what an external driver
  // publishes is read by the scene but written by nobody in it.
  const std::map<std::string, const PortSpec*>& read;
};
// Returns the ports; each one's name is its topic (default_topic), and it cannot be remapped.
// Throws std::runtime_error with a message for the user when the parameters do not make sense.
using ScenePortResolver = std::function<std::vector<PortSpec>(const ScenePortRequest&)>;

class ComponentSpec {
 public:
  std::string type;     // e.g. "motor_bridge"
  std::string summary;  // one line: what the component does

  template <typename Message>
  PortSpec& input(const std::string& name, const std::string& default_topic, QosPreset qos,
                  const std::string& doc) {
    return addPort({name, PortDirection::kInput, MessageType<Message>::kRosName, default_topic, qos, doc});
  }
  template <typename Message>
  PortSpec& output(const std::string& name, const std::string& default_topic, QosPreset qos,
                   const std::string& doc) {
    return addPort({name, PortDirection::kOutput, MessageType<Message>::kRosName, default_topic, qos, doc});
  }

  // Optional parameter with a default; the type follows the default's C++ type.
  ParameterSpec& param(const std::string& name, bool default_value, const std::string& doc);
  ParameterSpec& param(const std::string& name, int default_value, const std::string& doc);
  ParameterSpec& param(const std::string& name, double default_value, const std::string& doc);
  ParameterSpec& param(const std::string& name, const char* default_value, const std::string& doc);
  ParameterSpec& param(const std::string& name, std::vector<double> default_value, const std::string& doc);
  ParameterSpec& stringListParam(const std::string& name, std::vector<std::string> default_value,
                                 const std::string& doc);
  // A file path; empty default: none given. Non-empty values must name an existing file.
  ParameterSpec& pathParam(const std::string& name, const std::string& default_value, const std::string& doc);
  // A parameter the scene must set.
  ParameterSpec& requiredParam(const std::string& name, ParameterType type, const std::string& doc);

  // A rule between two string parameters that the scene validator checks, so that `uampc
  // validate` refuses what the component would refuse at start: when `parameter` is `value`,
  // `needed` must be `needed_value`, or, with no needed_value, a non-empty string (a file given).
  struct Requirement {
    std::string parameter, value, needed, needed_value;
  };
  void require(Requirement requirement) { requirements_.push_back(std::move(requirement)); }
  const std::vector<Requirement>& requirements() const { return requirements_; }

  // Ports only the scene can tell (which topics a recorder records, which a player publishes from
  // its file), decided when the scene is loaded, in addition to the declared ones. The component
  // opens them with Context::subscribeSerialized / serializedPublisher.
  void scenePorts(const std::string& doc, ScenePortResolver resolver) {
    scene_ports_doc_ = doc;
    scene_port_resolver_ = std::move(resolver);
  }
  const ScenePortResolver& scenePortResolver() const { return scene_port_resolver_; }
  const std::string& scenePortsDoc() const { return scene_ports_doc_; }

  // The declared ports (a scene instance's are ComponentInstance::ports).
  const std::vector<PortSpec>& ports() const { return ports_; }
  const std::vector<ParameterSpec>& parameters() const { return parameters_; }
  const PortSpec* findPort(const std::string& name) const;
  const ParameterSpec* findParameter(const std::string& name) const;

 private:
  PortSpec& addPort(PortSpec port);
  ParameterSpec& addParameter(ParameterSpec parameter);

  std::vector<PortSpec> ports_;
  std::vector<ParameterSpec> parameters_;
  std::vector<Requirement> requirements_;
  ScenePortResolver scene_port_resolver_;
  std::string scene_ports_doc_;
};

}  // namespace uampc
