// What the reader knows about a file before reading its messages: schemas, channels, where the
// chunks are and what they declare, message count and time range. Built from the summary when the
// footer and summary are valid, else by scanning the data section.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "file_io.hpp"
#include "records.hpp"
#include "uampc/mcap/mcap.hpp"

namespace uampc::mcap::detail {

struct ChunkLocation {
  std::uint64_t offset = 0;  // of the Chunk record's opcode byte
  std::uint64_t length = 0;  // of the whole record
  // What the chunk declares (the chunk index's copy when there is a summary); loading checks the
  // record against it.
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
  std::string compression;
  std::set<std::uint16_t> channels;  // channels with messages in the chunk; empty: not known
};

// A Message record outside any chunk (the spec allows them; uampc and rosbag2 do not write them).
struct LooseMessage {
  std::uint64_t offset = 0;  // of the record's opcode byte
  std::uint64_t length = 0;  // of the whole record
  std::uint64_t log_time = 0;
  std::uint16_t channel_id = 0;
};

struct FileIndex {
  HeaderRecord header;
  std::vector<Schema> schemas;
  std::vector<Channel> channels;
  std::vector<ChunkLocation> chunks;
  std::vector<LooseMessage> loose_messages;
  std::uint64_t message_count = 0;
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  bool recovered = false;
  std::vector<std::string> warnings;
};

// Throws McapError for a file that is not MCAP (bad magic, no Header record) or whose summary
// contradicts itself; a missing or damaged footer or summary is not an error (scan, warnings).
FileIndex indexFile(const InputFile& file);

}  // namespace uampc::mcap::detail
