#include "chunk_builder.hpp"

#include <algorithm>

namespace uampc::mcap::detail {

void ChunkBuilder::addMessage(const Schema* schema, const Channel& channel, const MessageRecord& message) {
  if (schema && schemas_written_.insert(schema->id).second) encode(records_, *schema);
  if (channels_written_.insert(channel.id).second) encode(records_, channel);
  message_index_[channel.id].emplace_back(message.log_time, records_.size());
  encode(records_, message);
  start_time_ = message_count_ == 0 ? message.log_time : std::min(start_time_, message.log_time);
  end_time_ = message_count_ == 0 ? message.log_time : std::max(end_time_, message.log_time);
  ++message_count_;
}

void ChunkBuilder::clear() {
  records_.clear();  // keeps its capacity: the next chunk fills the same buffer
  message_count_ = 0;
  start_time_ = end_time_ = 0;
  message_index_.clear();
  schemas_written_.clear();
  channels_written_.clear();
}

}  // namespace uampc::mcap::detail
