// `uampc topic list | echo TOPIC | hz TOPIC | bw TOPIC`: looking at a running system's topics from
// DDS discovery, like `ros2 topic` (docs/user/topics-and-recordings.md, "Looking at topics"). Works
// beside any DDS system on the domain, uampc's or another vendor's; echo decodes the types
// registered in this uampc (messageDefinition, cdr_decoder.hpp) and prints only the size of others.
#pragma once

#include "cli/command_set.hpp"

#include <functional>
#include <string>

namespace CLI {
class App;
}

namespace uampc::app {

// How long to wait by default. A Fast DDS participant answers a new participant's announcement at
// once, but on our machine that answer was missed in 17 of 53 starts of this tool's discovery
// beside a running scene: the scene was then found only at its next periodic announcement (every 3 s),
// 0.8 to 2.9 s after the start. So the default spans a whole announcement period, not ros2's 2 s.
constexpr double kDefaultWaitS = 3.5;
constexpr int kDefaultHzWindow = 10000;  // as ros2 topic hz
constexpr int kDefaultBwWindow = 100;    // as ros2 topic bw

enum class TopicAction { kList, kEcho, kHz, kBw };

struct TopicOptions {
  TopicAction action = TopicAction::kList;
  std::string topic;              // echo, hz, bw: a ROS name ("/motor/state") or, without a leading '/', a DDS name
  int domain_id = -1;             // -1: ROS_DOMAIN_ID if set, else 0
  double wait_s = kDefaultWaitS;  // list: how long discovery runs; echo, hz, bw: how long to wait for a writer
  bool verbose = false;           // list: every writer and reader with its participant
  int count = 0;                  // echo: stop after this many samples; 0: until Ctrl-C
  bool full = false;              // echo: print byte arrays whole
  int window = 0;                 // hz, bw: samples the figures are over; 0: the action's default
  std::string security_dir;       // a secured domain: DIR of uampc security init (its observer identity)
};

// Exit codes: 0 done (also on Ctrl-C, after the last report), 1 no writer of the topic or a DDS
// failure, 2 a bad ROS_DOMAIN_ID.
int topicCommand(const TopicOptions& options);

// Adds list, echo, hz and bw under `topic` (the `uampc topic` subcommand of main.cpp) with their
// options, parsed into `options`; add_synopsis(name, synopsis) is told each one's synopsis line.
void addTopicSubcommands(CLI::App& topic, TopicOptions& options,
                         const std::function<void(const std::string&, const std::string&)>& add_synopsis);

// `uampc topic list|echo|hz|bw` and their options.
void addTopicCommand(CommandSet& commands);

}  // namespace uampc::app
