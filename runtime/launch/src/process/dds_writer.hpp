// A component's output port on DDS (process_group.cpp): in lockstep each sample carries the step
// that wrote it, and the samples written are counted for the process's acknowledgements.
#pragma once

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <cstdint>
#include <string>
#include <utility>

#include "uampc/runtime/component.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/qos.hpp"

namespace uampc::process {

struct ProcessState;

class DdsWriter : public detail::Writer {
 public:
  DdsWriter(DdsNode& node, eprosima::fastdds::dds::DataWriter* writer, std::string topic, QosPreset qos,
            const ProcessState& state)
      : node_(node), writer_(writer), topic_(std::move(topic)), qos_(qos), state_(state) {}
  ~DdsWriter() override { node_.deleteWriter(writer_); }
  void write(const void* sample) override;
  eprosima::fastdds::dds::DataWriter* dds() const { return writer_; }
  const std::string& topic() const { return topic_; }
  std::uint64_t written() const { return written_; }

 private:
  DdsNode& node_;
  eprosima::fastdds::dds::DataWriter* writer_;
  std::string topic_;
  QosPreset qos_;
  const ProcessState& state_;
  std::uint64_t written_ = 0;
};

}  // namespace uampc::process
