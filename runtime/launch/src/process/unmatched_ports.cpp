#include "unmatched_ports.hpp"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>

#include "dds_writer.hpp"
#include "process_state.hpp"

namespace uampc::process {

using namespace eprosima::fastdds::dds;

std::string unmatchedPorts(const Scene& scene, const ProcessState& state) {
  std::string missing;
  for (const auto& w : state.writers) {
    PublicationMatchedStatus s;
    w->dds()->get_publication_matched_status(s);
    const int want = scene.readersOf(w->topic());
    if (s.current_count < want) {
      missing += "\n  writer on " + w->topic() + ": " + std::to_string(s.current_count) + " of " +
                 std::to_string(want) + " readers";
    }
  }
  for (const auto& r : state.dds_readers) {
    SubscriptionMatchedStatus s;
    r->reader->get_subscription_matched_status(s);
    const int want = scene.writersOf(r->topic);
    if (s.current_count < want) {
      missing += "\n  reader on " + r->topic + ": " + std::to_string(s.current_count) + " of " + std::to_string(want) +
                 " writers";
    }
  }
  return missing;
}

std::string securedStartHint(const Scene& scene) {
  if (scene.security_directory.empty()) return {};
  return "; in a secured run this can be a DDS Security handshake that Fast DDS 2.9 never completed (rare; "
         "docs/user/security.md, \"Known limitation\"): start the run again";
}

}  // namespace uampc::process
