// The chunk the writer is filling: its uncompressed records, one message index per channel, its
// time range, and the schemas and channels it already describes.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "records.hpp"

namespace uampc::mcap::detail {

class ChunkBuilder {
 public:
  // Appends the message, preceded by its schema and channel records the first time this chunk
  // sees them: each chunk then describes its own messages, so that the chunks of a file cut off
  // before its summary can be decoded on their own. `schema` is nullptr for schema id 0.
  void addMessage(const Schema* schema, const Channel& channel, const MessageRecord& message);

  bool empty() const { return message_count_ == 0; }
  std::uint64_t size() const { return records_.size(); }
  const Bytes& records() const { return records_; }
  std::uint64_t startTime() const { return start_time_; }
  std::uint64_t endTime() const { return end_time_; }
  // Channel id -> (log_time, offset of the Message record in records()), in write order.
  const std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>>& messageIndex() const {
    return message_index_;
  }

  void clear();

 private:
  Bytes records_;
  std::uint64_t message_count_ = 0;
  std::uint64_t start_time_ = 0;
  std::uint64_t end_time_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> message_index_;
  std::set<std::uint16_t> schemas_written_;
  std::set<std::uint16_t> channels_written_;
};

}  // namespace uampc::mcap::detail
