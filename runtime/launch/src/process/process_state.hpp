// What the parts of one process group share (process_group.cpp puts them together): the samples
// and input ports, the DDS readers behind them, the timers, and the process's clock and failure.
#pragma once

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/qos.hpp"
#include "uampc/runtime/time.hpp"
#include "../wakeup.hpp"

namespace uampc::process {

// A sample taken from a reader, owned until it is delivered.
struct Sample {
  std::shared_ptr<void> data;
  Time source_time;
};

struct ReaderPort;

// A DDS reader and the input ports it serves. Typed inputs of one process on one topic and QoS
// share one (Scene::readersOf): every DDS delivery costs the same whatever the sample's size (on
// Debian's Fast DDS build, several system calls of its debug checks), and the default loop's
// /motor/state alone has five readers in one process.
struct SharedReader {
  std::string topic;
  DdsNode* node = nullptr;  // the participant the reader belongs to
  eprosima::fastdds::dds::DataReader* reader = nullptr;
  eprosima::fastdds::dds::TypeSupport type;
  std::vector<ReaderPort*> ports;
  std::unique_ptr<ReaderActivity> activity;  // its listener; outlives the reader (deleted first)

  // Takes every sample the reader holds into each port's inbox, in arrival order.
  void poll();
};

// An input port of a component: its own view of its shared reader's samples.
struct ReaderPort {
  std::string component;
  std::string port;
  std::string topic;
  SharedReader* shared = nullptr;
  std::function<void(const void*, Time source_time)> callback;
  std::deque<Sample> inbox;     // taken from the DDS reader, not yet looked at by this port
  std::deque<Sample> deferred;  // lockstep: taken early, belongs to a later step
  std::uint64_t delivered = 0;  // samples handed to the callback so far

  // The samples its shared reader has taken for it so far, in arrival order.
  void drainInbox(std::deque<Sample>& out);
  // The same after taking what arrived since (a take costs DDS calls even on an empty reader).
  void takeAll(std::deque<Sample>& out);
};

// A reader with one port of its own: the clock's protocol topics.
struct ProtocolReader {
  SharedReader shared;
  ReaderPort port;
  ProtocolReader(DdsNode& node, const std::string& topic, const char* type_name, TypeSupportMaker type_support,
                 Wakeup* wakeup);
  ~ProtocolReader() { shared.node->deleteReader(shared.reader); }
  void takeAll(std::deque<Sample>& out) { port.takeAll(out); }
};

struct TimerEntry {
  std::string component;
  Time period;
  Time next;
  std::function<void()> callback;
};

class DdsWriter;

// State shared by the contexts of one process: the clock, the list of ports and timers, and why
// the process failed.
struct ProcessState {
  bool lockstep = false;
  bool started = false;  // false while components are being constructed
  Time now;
  Time step;
  Wakeup wakeup;
  std::vector<std::unique_ptr<ReaderPort>> readers;  // in the order components opened them
  std::vector<std::unique_ptr<SharedReader>> dds_readers;
  std::map<std::pair<std::string, QosPreset>, SharedReader*> typed_readers;  // by topic and QoS
  std::vector<std::shared_ptr<DdsWriter>> writers;  // the components' outputs, in the order opened
  std::vector<TimerEntry> timers;
  std::string failure;  // why the process failed, told in its acknowledgements; empty: it has not
};

// Samples written on each topic, by this process or summed over the processes' acknowledgements.
using TopicCounts = std::map<std::string, std::uint64_t>;

}  // namespace uampc::process
