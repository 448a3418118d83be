// The Context a component of a process group gets (process_group.cpp): its name, parameters,
// time and timers, and its ports opened as the process's DDS readers and writers.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "uampc/runtime/component.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/logger.hpp"
#include "uampc/runtime/scene.hpp"
#include "process_state.hpp"

namespace uampc::process {

class ContextImpl : public Context {
 public:
  // serialized_dds: the participant of the process's serialized ports, made on first use.
  ContextImpl(const Scene& scene, const ComponentInstance& instance, const std::string& output_directory, DdsNode& dds,
              std::function<DdsNode&()> serialized_dds, ProcessState& state);

  const std::string& name() const override { return instance_.name; }
  const Logger& log() const override { return logger_; }
  Time now() const override { return state_.now; }
  std::uint64_t seed() const override { return scene_.seed; }
  const std::string& outputDirectory() const override { return output_directory_; }
  bool lockstep() const override { return state_.lockstep; }
  Time step() const override { return state_.lockstep ? state_.step : Time{0}; }

  void timer(double period_s, std::function<void()> callback) override;

  bool paramBool(const std::string& n) const override { return std::get<bool>(param(n)); }
  std::int64_t paramInt(const std::string& n) const override { return std::get<std::int64_t>(param(n)); }
  double paramDouble(const std::string& n) const override;
  std::string paramString(const std::string& n) const override { return std::get<std::string>(param(n)); }
  std::vector<double> paramDoubleList(const std::string& n) const override {
    return std::get<std::vector<double>>(param(n));
  }
  std::vector<std::string> paramStringList(const std::string& n) const override {
    return std::get<std::vector<std::string>>(param(n));
  }
  const std::vector<PortSpec>& ports() const override { return instance_.ports; }
  std::string topicOf(const std::string& port) const override;

  // Declared ports the component opened neither a publisher nor a subscription on. The start of a
  // run waits until every declared port is matched, so such a port would stall it.
  std::vector<std::string> unopenedPorts() const;

 protected:
  std::shared_ptr<detail::Writer> makeWriter(const std::string& port, const char* type_name,
                                             detail::TypeSupportFactory type_support) override;

  void addReader(const std::string& port, const char* type_name, detail::TypeSupportFactory type_support,
                 std::function<void(const void*)> callback) override;

  // Serialized ports live on a participant of their own: one participant registers one type
  // support per type name, and the process's typed ports of the same type have theirs.
  std::shared_ptr<detail::Writer> makeSerializedWriter(const std::string& port) override;

  void addSerializedReader(const std::string& port,
                           std::function<void(const SerializedMessage&, Time)> callback) override;

 private:
  const ParameterValue& param(const std::string& n) const;
  std::shared_ptr<detail::Writer> openWriter(const std::string& port, DdsNode& node,
                                             const TypeSupportMaker& type_support, const PortSpec& spec);

  void openReader(const std::string& port, DdsNode& node, const TypeSupportMaker& type_support, const PortSpec& spec,
                  std::function<void(const void*, Time)> callback);

  SharedReader* newDdsReader(DdsNode& node, const std::string& topic, const TypeSupportMaker& type_support,
                             const PortSpec& spec);

  // The process's typed reader of the topic with the port's QoS, made on first use.
  SharedReader* typedReader(const std::string& topic, const TypeSupportMaker& type_support, const PortSpec& spec);

  static TypeSupportMaker serializedTypeSupport(const PortSpec& spec);

  const PortSpec& checkPort(const std::string& port, PortDirection direction, const char* type_name) const;

  const Scene& scene_;
  const ComponentInstance& instance_;
  std::string output_directory_;
  DdsNode& dds_;
  std::function<DdsNode&()> serialized_dds_;
  ProcessState& state_;
  std::set<std::string> opened_ports_;
  Logger logger_;
};

}  // namespace uampc::process
