// `uampc play FILE.mcap [--domain N] [--rate R] [--start S] [--topics T ...] [--loop] [--clock]
// [--wait-for-readers]`:
// publishes a recording's samples with their recorded timing, in real time, beside a running
// system (the player component does the same inside a scene, also in lockstep).
#pragma once

#include "cli/command_set.hpp"

#include <string>
#include <vector>

#include "uampc/runtime/viewer_process.hpp"

namespace uampc::app {

struct PlayOptions {
  std::string file;
  int domain_id = -1;  // -1: ROS_DOMAIN_ID, else 0
  double rate = 1.0;
  double start_s = 0.0;
  std::vector<std::string> topics;  // empty: all
  bool loop = false;
  bool clock = false;             // publish /clock with the recording's time
  bool wait_for_readers = false;  // start once every topic has a reader (a recorder, the system under test)
  bool restamp = false;           // move stamps to the present (recording/restamp.hpp)
  std::string security_dir;       // a secured domain: DIR of uampc security init (its player identity)
  ViewerOptions viewer;           // --view: a live viewer of what is played, from when a client subscribes
};

// Exit codes: 0 at the end of the recording, 1 for a bad recording or DDS failure, 130 on Ctrl-C.
int playCommand(const PlayOptions& options);

// `uampc play` and its options.
void addPlayCommand(CommandSet& commands);

}  // namespace uampc::app
