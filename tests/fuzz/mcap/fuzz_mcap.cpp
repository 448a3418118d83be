// MCAP files as `uampc play`, the player component and replay read them (libs/mcap): the
// Reader (footer, summary, chunk indexes, or a scan of the data section when those are bad),
// every message in log-time order with forEachMessage, and a MessageStream restricted to one
// topic from a start time, as Playback uses it. Bad input must end in McapError naming the file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_input_file.hpp"
#include "uampc/mcap/mcap.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace uampc;
  const std::string path = fuzz::writeInputFile(data, size, "recording.mcap");
  try {
    mcap::Reader reader(path);
    std::uint64_t sum = 0;  // touches every byte handed out, for ASan
    for (const auto& s : reader.schemas()) sum += s.data.size();
    std::vector<std::string> topics;
    for (const auto& c : reader.channels()) topics.push_back(c.topic);
    sum += reader.messageCount() + reader.startTime() + reader.endTime();
    reader.forEachMessage({}, 0, [&](const mcap::MessageView& m) {
      for (std::size_t i = 0; i < m.size; ++i) sum += m.data[i];
      sum += m.channel->topic.size();
      return true;
    });
    if (!topics.empty()) {
      const std::uint64_t middle = reader.startTime() / 2 + reader.endTime() / 2;
      mcap::MessageStream stream = reader.messages({topics.front()}, middle);
      for (mcap::MessageView m; stream.next(m);) {
        for (std::size_t i = 0; i < m.size; ++i) sum += m.data[i];
      }
    }
    if (sum == 1) return 0;  // keeps the sum alive
  } catch (const mcap::McapError&) {
  }
  return 0;
}
