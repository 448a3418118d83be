// `uampc record -o FILE.mcap [--domain N] [TOPIC ...]`: records the topics of a running system
// (every ROS topic it discovers, by default) to an MCAP file as rosbag2 writes it, beside any
// system on the domain, uampc's or another vendor's. Inside a scene, use the recorder component.
#pragma once

#include "cli/command_set.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace uampc::app {

struct RecordOptions {
  std::string output;
  bool overwrite = false;           // replace an existing output file (docs/decisions/no-silent-overwrite.md)
  int domain_id = -1;               // -1: ROS_DOMAIN_ID, else 0
  std::vector<std::string> topics;  // ROS names; empty: every ROS topic discovered
  std::string compression = "zstd";
  std::uint64_t chunk_size = 4 * 1024 * 1024;
  double duration_s = 0.0;   // 0: until Ctrl-C
  std::string security_dir;  // a secured domain: DIR of uampc security init (its observer identity)
};

// Exit codes: 0 when stopped by Ctrl-C, SIGTERM or --duration (the file is complete), 1 on errors
// (an existing output file without overwrite among them: refused before anything is recorded).
int recordCommand(const RecordOptions& options);

// `uampc record` and its options.
void addRecordCommand(CommandSet& commands);

}  // namespace uampc::app
