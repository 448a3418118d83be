#include "process_state.hpp"

#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace uampc::process {

using namespace eprosima::fastdds::dds;

void ReaderPort::drainInbox(std::deque<Sample>& out) {
  for (auto& s : inbox) out.push_back(std::move(s));
  inbox.clear();
}

void ReaderPort::takeAll(std::deque<Sample>& out) {
  shared->poll();
  drainInbox(out);
}

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

ProtocolReader::ProtocolReader(DdsNode& node, const std::string& topic, const char* type_name,
                               TypeSupportMaker type_support, Wakeup* wakeup) {
  shared.topic = port.topic = topic;
  shared.node = &node;
  shared.type = TypeSupport(type_support());
  shared.activity = std::make_unique<ReaderActivity>(*wakeup);
  shared.reader = node.createReader(topic, type_name, type_support, QosPreset::kControl, shared.activity.get());
  shared.ports.push_back(&port);
  port.shared = &shared;
}

}  // namespace uampc::process
