#include "bag/play_command.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <thread>

#include "cli/command_set.hpp"
#include "uampc/command_line/finite_number.hpp"
#include "uampc/msgs/rosgraph_msgs.hpp"
#include "uampc/recording/playback.hpp"
#include "uampc/recording/restamp.hpp"
#include "uampc/runtime/dds_names.hpp"
#include "uampc/runtime/dds_node.hpp"
#include "uampc/runtime/lockstep_topics.hpp"
#include "uampc/runtime/process_group.hpp"
#include "uampc/runtime/stop_signals.hpp"
#include "uampc/runtime/wall_clock.hpp"

namespace uampc::app {

namespace {

using SteadyClock = std::chrono::steady_clock;
using eprosima::fastdds::dds::DataWriter;

constexpr double kClockRate = 100.0;  // Hz of /clock, as `ros2 bag play --clock` defaults to

// Time spent in DataWriter::write per topic: `uampc play` prints it, the figure behind "replay
// publishes a 20k-point scan in under 1 ms".
struct PublishCost {
  std::uint64_t samples = 0;
  std::uint64_t bytes = 0;
  double total_s = 0.0;
  double max_s = 0.0;
};

// Where a pass starts on the recording's time line: its first sample, or --start seconds after.
Time playOrigin(const recording::Playback& playback, const PlayOptions& options) {
  return playback.start() + Time::fromSeconds(options.start_s);
}

// What a pass will play, said before it starts: the topics, the samples of them due from the
// origin on (after --topics and --start), and the seconds from there to the end.
void announce(recording::Playback& playback, const PlayOptions& options, int domain) {
  const Time origin = playOrigin(playback, options);
  std::cerr << "uampc play: " << options.file << ": " << playback.topics().size() << " topics, "
            << playback.samplesDueFrom(origin) << " samples, " << std::max(0.0, (playback.end() - origin).seconds())
            << " s, on domain " << domain << "\n";
}

class Player {
 public:
  Player(const PlayOptions& options, recording::Playback& playback, DdsNode& dds)
      : options_(options), playback_(playback), costs_(playback.topics().size()) {
    for (const auto& topic : playback.topics()) {
      const std::string dds_type = ddsTypeName(topic.type);
      writers_.push_back(dds.createWriter(
          topic.topic, topic.type, [dds_type] { return SerializedTypeSupport::forDdsType(dds_type); }, topic.qos));
    }
    if (options.clock) {
      clock_writer_ = dds.createWriter(kClockTopic, MessageType<rosgraph_msgs::msg::Clock>::kRosName,
                                       &detail::makeTypeSupport<rosgraph_msgs::msg::Clock>, QosPreset::kControl);
    }
  }

  // The viewer beside the playing (--view): if it fails, so does the playing.
  void watchViewer(ViewerProcess* viewer) { viewer_ = viewer; }

  // every_topic false: until one topic has a reader (a viewer's client that subscribed). False
  // when stopped by a signal.
  bool waitForReaders(bool every_topic) const {
    auto next_report = SteadyClock::now() + std::chrono::seconds(2);
    for (;;) {
      std::string missing;
      bool some_read = false;
      for (std::size_t i = 0; i < writers_.size(); ++i) {
        if (!writers_[i]) continue;
        eprosima::fastdds::dds::PublicationMatchedStatus status;
        writers_[i]->get_publication_matched_status(status);
        if (status.current_count < 1) missing += " " + playback_.topics()[i].topic;
        some_read = some_read || status.current_count > 0;
      }
      if (every_topic ? missing.empty() : some_read) return true;
      if (stopRequested()) return false;
      throwIfViewerFailed();
      if (SteadyClock::now() > next_report) {
        if (every_topic) {
          std::cerr << "uampc play: waiting for readers of" << missing << "\n";
        } else {
          std::cerr << "uampc play: waiting for a viewer's client to subscribe to a topic\n";
        }
        next_report += std::chrono::seconds(5);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }

  // Plays once through; false when stopped by a signal.
  bool playOnce() {
    const auto started = SteadyClock::now();
    const Time origin = playOrigin(playback_, options_);
    // Each pass starts now: its samples' stamps move by the same offset as its time line.
    restamper_.setOffset(options_.restamp ? wallNow() - origin : Time{0});
    playback_.seek(origin);  // from the start, or past what --start skips without reading it
    const double length_s = (playback_.end() - origin).seconds();
    auto next_progress = started;
    auto next_clock = started;
    recording::RecordedSample sample;
    while (!playback_.finished()) {
      if (stopRequested()) return false;
      throwIfViewerFailed();
      const auto now = SteadyClock::now();
      const double elapsed_s = std::chrono::duration<double>(now - started).count() * options_.rate;
      const Time until = origin + Time::fromSeconds(elapsed_s);
      while (playback_.next(until, sample)) {
        if (sample.time < origin) continue;  // before --start
        publish(sample);
      }
      if (clock_writer_ && now >= next_clock) {
        rosgraph_msgs::msg::Clock clock;
        clock.clock(toMsg(until + restamper_.offset()));
        clock_writer_->write(&clock);
        next_clock +=
            std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(1.0 / kClockRate));
      }
      if (now >= next_progress) {
        std::fprintf(stderr, "\r  playing %.1f / %.1f s", std::min(elapsed_s, length_s), length_s);
        next_progress += std::chrono::seconds(1);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::fprintf(stderr, "\r  played %.1f s%20s\n", length_s, "");
    return true;
  }

  void printCosts() const {
    std::cout << "topic, samples, MB, publish ms mean / max\n";
    for (std::size_t i = 0; i < costs_.size(); ++i) {
      const PublishCost& c = costs_[i];
      if (c.samples == 0) continue;
      std::printf("%s, %llu, %.1f, %.3f / %.3f\n", playback_.topics()[i].topic.c_str(),
                  static_cast<unsigned long long>(c.samples), c.bytes / 1e6, 1e3 * c.total_s / c.samples,
                  1e3 * c.max_s);
    }
  }

 private:
  // A play asked to be watched fails without its viewer (docs/decisions/run-fails-with-its-viewer.md).
  void throwIfViewerFailed() const {
    if (!viewer_) return;
    if (const std::string problem = viewer_->poll(); !problem.empty()) throw std::runtime_error(problem);
  }

  void publish(recording::RecordedSample& sample) {
    DataWriter* writer = writers_[sample.topic];
    if (!writer) return;
    const auto t0 = SteadyClock::now();
    if (options_.restamp) {
      restamper_.restamp(playback_.topics()[sample.topic].topic, playback_.topics()[sample.topic].type, sample.data);
    }
    if (writer->write(&sample.data) != true) {
      throw std::runtime_error("publishing on " + playback_.topics()[sample.topic].topic + " failed");
    }
    const double dt = std::chrono::duration<double>(SteadyClock::now() - t0).count();
    PublishCost& c = costs_[sample.topic];
    ++c.samples;
    c.bytes += sample.data.data.size();
    c.total_s += dt;
    c.max_s = std::max(c.max_s, dt);
  }

  const PlayOptions& options_;
  recording::Playback& playback_;
  std::vector<DataWriter*> writers_;  // by topic index; null: not played
  DataWriter* clock_writer_ = nullptr;
  std::vector<PublishCost> costs_;
  recording::Restamper restamper_{Time{0}};
  ViewerProcess* viewer_ = nullptr;
};

// Recorded /clock and lockstep protocol topics are never played: on a live domain, the run there
// would take them for another run's (docs/decisions/replay-leaves-lockstep-topics.md).
void sayWhatIsNotPlayed(const recording::Playback& playback, const PlayOptions& options) {
  for (const std::string& topic : playback.skipped()) {
    std::cerr << "uampc play: not playing " << topic << ": a lockstep run's own topic"
              << (topic == kClockTopic && !options.clock ? " (--clock publishes one from the recording's time line)"
                                                         : "")
              << "\n";
  }
}

}  // namespace

int playCommand(const PlayOptions& options) {
  try {
    const int domain = options.domain_id >= 0 ? options.domain_id : rosDomainIdFromEnvironment().value_or(0);
    if (options.viewer.enabled) {
      if (const std::string problem = viewerAddressProblem(options.viewer); !problem.empty()) {
        throw std::runtime_error("--view: " + problem);
      }
    }
    recording::Playback playback(options.file, options.topics);
    for (const auto& warning : playback.warnings()) std::cerr << "uampc play: warning: " << warning << "\n";
    sayWhatIsNotPlayed(playback, options);
    if (playback.topics().empty()) throw std::runtime_error(options.file + ": the recording has no topics to play");
    DdsNode dds(domain, "", false, "uampc/play", checkedSecurityIdentity(options.security_dir, kPlayerIdentity));
    Player player(options, playback, dds);
    announce(playback, options, domain);
    catchStopSignals();
    std::unique_ptr<ViewerProcess> viewer;
    if (options.viewer.enabled) viewer = std::make_unique<ViewerProcess>(options.viewer, domain, options.security_dir);
    player.watchViewer(viewer.get());
    if (options.wait_for_readers || viewer) {
      // With a viewer: from when its client looks, not before (the user is still opening it).
      if (!player.waitForReaders(options.wait_for_readers)) return 130;
    } else {
      // Give readers a moment to match before the first samples go out, as ros2 bag play does.
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    do {
      if (!player.playOnce()) {
        player.printCosts();
        return 130;
      }
    } while (options.loop);
    player.printCosts();
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "uampc play: error: " << e.what() << "\n";
    return 1;
  }
}

void addPlayCommand(CommandSet& commands) {
  auto options = std::make_shared<PlayOptions>();
  PlayOptions& o = *options;
  CLI::App* sub = commands.add(
      "play",
      "uampc play FILE.mcap [--domain N] [--rate R] [--start S] [--topics TOPIC ...] [--loop]\n[--clock] "
      "[--wait-for-readers] [--restamp] [--security DIR] [--view [--view-port P] [--view-address A] [--view-max-...]]",
      "Publish a recording's samples (MCAP as rosbag2 and uampc's recorder write it) with their recorded\n"
      "timing, in real time; prints the cost of each topic's publishing at the end. Inside a lockstep scene,\n"
      "use the player component instead (config/scenes/replay_lo.yaml).");
  sub->add_option("FILE.mcap", o.file, "The recording.")->required()->type_name("");
  sub->add_option("--domain", o.domain_id, "DDS domain (default: ROS_DOMAIN_ID, else 0).")
      ->check(CLI::Range(0, uampc::kMaxDomainId))
      ->type_name("N");
  sub->add_option("--rate", o.rate, "Playback speed: 2 plays twice as fast (default 1).")
      ->check(command_line::kFinite)
      ->check(CLI::Range(0.01, 100.0))
      ->type_name("R");
  sub->add_option("--start", o.start_s, "Skip the recording's first S seconds.")
      ->check(command_line::kFiniteNonNegative)
      ->type_name("S");
  sub->add_option("--topics", o.topics, "Play only these topics (default: all).")->type_name("TOPIC ...");
  sub->add_flag("--loop", o.loop, "Start over at the end, until Ctrl-C.");
  sub->add_flag("--clock", o.clock,
                "Publish /clock (100 Hz) with the recording's time, as ros2 bag play --clock. A recorded /clock\n"
                "and the lockstep protocol's topics (/uampc/lockstep/...) are never played.");
  sub->add_flag("--wait-for-readers", o.wait_for_readers,
                "Start only once every played topic has a reader (else after 0.5 s), so that no sample goes\n"
                "out before the system under test or a recorder hears it.");
  sub->add_flag("--restamp", o.restamp,
                "Move every header stamp (and a PointCloud2's absolute point times) to the present, as if the\n"
                "recording were happening now: for a real-time system that pairs the played samples with live ones\n"
                "by stamp (a recorded LiDAR beside a live motor, docs/user/rig.md).");
  sub->add_option("--security", o.security_dir,
                  "Join a secured domain with the player identity of DIR (uampc security init), which may\n"
                  "publish every topic, the motor's commands too.")
      ->type_name("DIR");
  addViewerOptions(sub, o.viewer);
  commands.onRun(sub, [options] { return playCommand(*options); });
}

}  // namespace uampc::app
