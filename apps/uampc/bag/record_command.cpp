#include "bag/record_command.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "cli/command_set.hpp"
#include "topic/raw_subscription.hpp"
#include "topic/topic_discovery.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/recording/recording_writer.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/file_checks.hpp"
#include "uampc/runtime/lockstep_topics.hpp"
#include "uampc/runtime/message_type.hpp"
#include "uampc/runtime/stop_signals.hpp"

namespace uampc::app {

namespace {

using SteadyClock = std::chrono::steady_clock;

constexpr auto kPollPeriod = std::chrono::milliseconds(20);
constexpr auto kProgressPeriod = std::chrono::seconds(5);

// The preset that describes a discovered writer's QoS best, for the recording's metadata and for a
// player that offers it again.
QosPreset presetOf(const DiscoveredEndpoint& writer) {
  if (writer.transient_local) return QosPreset::kLatched;
  return writer.reliable ? QosPreset::kControl : QosPreset::kSensor;
}

// Samples arrive on Fast DDS's threads; the file is written from the main thread only.
struct Arrival {
  std::size_t topic;
  SampleTimes times;
  SerializedMessage sample;
};

class Recorder {
 public:
  Recorder(const RecordOptions& options, int domain)
      : options_(options),
        discovery_(domain, checkedSecurityIdentity(options.security_dir, kObserverIdentity)),
        writer_(options.output, recordingOptions(options)) {}

  // Subscribes to the topics discovered since the last call that are to be recorded.
  void subscribeNewTopics() {
    for (const auto& [dds_name, topic] : discovery_.topics()) {
      if (topic.writers.empty() || subscribed_.count(dds_name)) continue;
      const std::string name = rosTopicName(dds_name);
      if (name.empty()) continue;  // not a ROS topic (DDS's own or a vendor's internals)
      if (!options_.topics.empty() && !wanted(name)) continue;
      subscribed_.insert(dds_name);
      if (options_.topics.empty() && isLockstepProtocolTopic(name)) {
        // Not the run's data; played back onto a live domain they would stop the run there
        // (docs/decisions/replay-leaves-lockstep-topics.md). Named on the command line, they are kept.
        std::cerr << "uampc record: leaving out " << name << ": the lockstep protocol's (name it to record it)\n";
        continue;
      }
      const DiscoveredEndpoint& writer = topic.writers.front();
      const std::string type = rosTypeName(writer.type);
      if (type.empty()) {
        std::cerr << "uampc record: skipping " << name << ": its type " << writer.type
                  << " does not follow ROS 2's naming, so no ros2msg schema can name it\n";
        continue;
      }
      bool unknown_type = false;
      const std::size_t index = writer_.addTopic({name, type, presetOf(writer)}, &unknown_type);
      names_.push_back(name);
      counts_.push_back(0);
      if (unknown_type) {
        std::cerr << "uampc record: " << name << ": type " << type << " is not known to uampc: recorded without "
                  << "its definition (tools that decode will not know how)\n";
      }
      subscriptions_.push_back(std::make_unique<RawSubscription>(
          discovery_.participant(), topic, [this, index](SerializedMessage&& sample, const SampleTimes& t) {
            std::lock_guard<std::mutex> lock(mutex_);
            arrivals_.push_back({index, t, std::move(sample)});
          }));
      std::cerr << "uampc record: recording " << name << " (" << type << ")\n";
    }
  }

  void writeArrived() {
    std::deque<Arrival> arrived;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      arrived.swap(arrivals_);
    }
    for (const Arrival& a : arrived) {
      writer_.write(a.topic, a.times.received, a.times.published, a.sample);
      ++counts_[a.topic];
      bytes_ += a.sample.data.size();
    }
  }

  void close() {
    subscriptions_.clear();  // no more arrivals
    writeArrived();
    writer_.close();
  }

  void printProgress(double elapsed_s) const {
    std::fprintf(stderr, "uampc record: %.0f s, %llu samples (%.1f MB) on %zu topics\n", elapsed_s,
                 static_cast<unsigned long long>(writer_.messages()), bytes_ / 1e6, names_.size());
  }

  void printSummary(double elapsed_s) const {
    const double file_mb = std::filesystem::file_size(options_.output) / 1e6;
    std::cout << "topic, samples\n";
    for (std::size_t i = 0; i < names_.size(); ++i) std::cout << names_[i] << ", " << counts_[i] << "\n";
    std::printf("%s: %llu samples, %.1f MB of samples in %.1f MB of file, %.1f s (%.0f MB per minute)\n",
                options_.output.c_str(), static_cast<unsigned long long>(writer_.messages()), bytes_ / 1e6, file_mb,
                elapsed_s, elapsed_s > 0 ? file_mb * 60.0 / elapsed_s : 0.0);
  }

  std::vector<std::string> missingTopics() const {
    std::vector<std::string> missing;
    for (const std::string& t : options_.topics) {
      if (!subscribed_.count(ddsTopicName(t))) missing.push_back(t);
    }
    return missing;
  }

 private:
  static recording::RecordingOptions recordingOptions(const RecordOptions& o) {
    recording::RecordingOptions r;
    r.compression = recording::compressionByName(o.compression);
    r.chunk_size = o.chunk_size;
    r.clock = recording::RecordingClock::kRealtime;
    return r;
  }
  bool wanted(const std::string& name) const {
    for (const std::string& t : options_.topics) {
      if (t == name) return true;
    }
    return false;
  }

  const RecordOptions& options_;
  TopicDiscovery discovery_;
  recording::RecordingWriter writer_;
  std::set<std::string> subscribed_;  // DDS topic names
  std::vector<std::unique_ptr<RawSubscription>> subscriptions_;
  std::vector<std::string> names_;  // by topic index
  std::vector<std::uint64_t> counts_;
  std::uint64_t bytes_ = 0;
  std::mutex mutex_;
  std::deque<Arrival> arrivals_;
};

// An existing recording is not replaced without --overwrite (docs/decisions/no-silent-overwrite.md):
// a 50 MB recording became a 165-byte one. Only regular files: a device (/dev/null) is written as
// before, and a directory fails in the writer with its own message.
void refuseExistingOutput(const RecordOptions& options) {
  if (options.overwrite || !isRegularFile(options.output)) return;
  throw std::runtime_error(options.output + " exists; give --overwrite to replace it, or another -o FILE.mcap");
}

}  // namespace

int recordCommand(const RecordOptions& options) {
  try {
    for (const std::string& t : options.topics) {
      if (t.empty() || t.front() != '/') throw std::runtime_error("'" + t + "' is not a ROS topic name (/name/space)");
    }
    refuseExistingOutput(options);
    const int domain = options.domain_id >= 0 ? options.domain_id : rosDomainIdFromEnvironment().value_or(0);
    catchStopSignals();
    Recorder recorder(options, domain);
    std::cerr << "uampc record: writing " << options.output << " from domain " << domain << " (Ctrl-C stops)\n";
    const auto started = SteadyClock::now();
    auto next_progress = started + kProgressPeriod;
    auto elapsed = [&] { return std::chrono::duration<double>(SteadyClock::now() - started).count(); };
    while (!stopRequested() && (options.duration_s <= 0 || elapsed() < options.duration_s)) {
      recorder.subscribeNewTopics();
      recorder.writeArrived();
      if (SteadyClock::now() >= next_progress) {
        recorder.printProgress(elapsed());
        for (const std::string& t : recorder.missingTopics()) {
          std::cerr << "uampc record: still waiting for a writer of " << t << " on domain " << domain << "\n";
        }
        next_progress += kProgressPeriod;
      }
      std::this_thread::sleep_for(kPollPeriod);
    }
    recorder.close();
    recorder.printSummary(elapsed());
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "uampc record: error: " << e.what() << "\n";
    return 1;
  }
}

void addRecordCommand(CommandSet& commands) {
  auto options = std::make_shared<RecordOptions>();
  RecordOptions& o = *options;
  CLI::App* sub = commands.add(
      "record",
      "uampc record -o FILE.mcap [--overwrite] [--domain N] [--compression zstd|lz4|none]\n"
      "[--chunk-size BYTES] [--duration S] [--security DIR] [TOPIC ...]",
      "Record the topics of a running system (every ROS topic discovered on the domain, of uampc or any\n"
      "other DDS vendor, by default) to an MCAP file as rosbag2 writes it (Foxglove, ros2 bag, uampc play).\n"
      "Ctrl-C stops it and completes the file. Inside a scene, use the recorder component.");
  sub->add_option("-o,--output", o.output, "The file to write; an existing one only with --overwrite.")
      ->required()
      ->type_name("FILE.mcap");
  sub->add_flag("--overwrite", o.overwrite,
                "Replace -o FILE.mcap if it exists (without it, an existing file is refused).");
  sub->add_option("TOPIC", o.topics,
                  "Topics to record (default: all but the lockstep protocol's, /uampc/lockstep/...; name one to\n"
                  "record it).")
      ->type_name("");
  sub->add_option("--domain", o.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0).")
      ->check(CLI::Range(0, uampc::kMaxDomainId))
      ->type_name("N");
  sub->add_option("--compression", o.compression, "Chunk compression: zstd (default), lz4 or none.")
      ->check(CLI::IsMember({"zstd", "lz4", "none"}).description(""))
      ->type_name("zstd|lz4|none");
  sub->add_option("--chunk-size", o.chunk_size,
                  "Bytes of samples per chunk (default 4 MiB); a killed recorder loses at most the last three chunks.")
      ->check(CLI::Range(std::uint64_t{1024}, std::uint64_t{1} << 30))
      ->type_name("BYTES");
  sub->add_option("--duration", o.duration_s, "Stop after S seconds (default: at Ctrl-C).")
      ->check(command_line::kFiniteNonNegative)
      ->type_name("S");
  sub->add_option("--security", o.security_dir,
                  "Join a secured domain with the observer identity of DIR (uampc security init), which may\n"
                  "read every topic.")
      ->type_name("DIR");
  commands.onRun(sub, [options] { return recordCommand(*options); });
}

}  // namespace uampc::app
