#include "dds_writer.hpp"

#include <stdexcept>

#include "process_state.hpp"

namespace uampc::process {

using namespace eprosima::fastdds::dds;

void DdsWriter::write(const void* sample) {
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

}  // namespace uampc::process
