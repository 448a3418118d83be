// How long a point cloud takes from one process to another over Fast DDS, as the runtime's
// participants move it (the speed target: a 20k-point PointCloud2 in at most 0.5 ms median). A bench
// command that prints figures, not a Google Benchmark: it needs two processes.
//
//   dds_transfer_bench [--points N] [--samples K] [--profile FILE.xml] [--domain D]
//
// The parent writes a cloud of N points (16 bytes each, as the raycaster's x y z intensity) with
// the lockstep QoS (reliable, keep all); a forked child takes it and answers with an empty cloud.
// Round trips of the full cloud and of an empty one are timed; the one-way time of the full cloud
// is its round trip less half the empty one's. --profile: a Fast DDS XML profile (e.g.
// config/dds/large_data.xml); default: Fast DDS's built-in transports (shared memory + UDP).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "../src/wakeup.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/runtime/dds_node.hpp"

namespace {

using namespace eprosima::fastdds::dds;
using Cloud = sensor_msgs::msg::PointCloud2;
using SteadyClock = std::chrono::steady_clock;

constexpr char kPing[] = "/bench/ping";
constexpr char kPong[] = "/bench/pong";

struct Options {
  int points = 20000;
  int samples = 200;
  std::string profile;
  int domain = 7;
};

Cloud cloudOf(int points) {
  Cloud c;
  c.header().frame_id("lidar");
  c.height(1);
  c.width(static_cast<std::uint32_t>(points));
  c.point_step(16);
  c.row_step(16u * static_cast<std::uint32_t>(points));
  c.data().assign(static_cast<std::size_t>(points) * 16, 0x5a);
  return c;
}

struct Endpoint {
  uampc::DdsNode node;
  uampc::Wakeup wakeup;
  DataWriter* writer;
  DataReader* reader;
  Endpoint(const Options& o, const char* name, const char* out, const char* in)
      : node(o.domain, o.profile, true, name),
        writer(node.createWriter(out, uampc::MessageType<Cloud>::kRosName, &uampc::detail::makeTypeSupport<Cloud>,
                                 uampc::QosPreset::kSensor)),
        reader(node.createReader(in, uampc::MessageType<Cloud>::kRosName, &uampc::detail::makeTypeSupport<Cloud>,
                                 uampc::QosPreset::kSensor, &wakeup)) {}
  ~Endpoint() {
    node.deleteWriter(writer);
    node.deleteReader(reader);
  }
  bool matched() {
    PublicationMatchedStatus p;
    SubscriptionMatchedStatus s;
    writer->get_publication_matched_status(p);
    reader->get_subscription_matched_status(s);
    return p.current_count > 0 && s.current_count > 0;
  }
  // The next sample, waiting at most `timeout`; false on timeout.
  bool take(Cloud& sample, std::chrono::milliseconds timeout) {
    const auto deadline = SteadyClock::now() + timeout;
    SampleInfo info;
    for (;;) {
      if (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK && info.valid_data) return true;
      if (SteadyClock::now() > deadline) return false;
      wakeup.waitUntil(std::min(deadline, SteadyClock::now() + std::chrono::milliseconds(5)));
    }
  }
};

// The child: answers every cloud with an empty one until it gets one framed "stop".
int echo(const Options& o) {
  Endpoint e(o, "bench/echo", kPong, kPing);
  Cloud in, empty = cloudOf(0);
  while (e.take(in, std::chrono::milliseconds(30000))) {
    if (in.header().frame_id() == "stop") return 0;
    empty.header().stamp(in.header().stamp());
    e.writer->write(&empty);
  }
  return 1;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

// Round trips of `cloud`, in ms; empty on a lost answer.
std::vector<double> roundTrips(Endpoint& e, Cloud cloud, int samples) {
  std::vector<double> ms;
  Cloud answer;
  for (int i = 0; i < samples; ++i) {
    cloud.header().stamp().sec(i);
    const auto start = SteadyClock::now();
    e.writer->write(&cloud);
    if (!e.take(answer, std::chrono::milliseconds(5000))) return {};
    ms.push_back(std::chrono::duration<double, std::milli>(SteadyClock::now() - start).count());
  }
  return ms;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "--points" && value) {
      o.points = std::atoi(argv[++i]);
    } else if (a == "--samples" && value) {
      o.samples = std::atoi(argv[++i]);
    } else if (a == "--profile" && value) {
      o.profile = argv[++i];
    } else if (a == "--domain" && value) {
      o.domain = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: dds_transfer_bench [--points N] [--samples K] [--profile FILE.xml] [--domain D]\n");
      std::exit(a == "--help" ? 0 : 2);
    }
  }
  if (o.points < 0 || o.samples < 1 || o.domain < 0 || o.domain > 232) {
    std::fprintf(stderr, "dds_transfer_bench: --points >= 0, --samples >= 1, --domain 0..232\n");
    std::exit(2);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const pid_t child = fork();  // before any DDS entity exists in this process
  if (child == 0) _exit(echo(o));
  int code = 1;
  {
    Endpoint e(o, "bench/source", kPing, kPong);
    const auto deadline = SteadyClock::now() + std::chrono::seconds(20);
    while (!e.matched() && SteadyClock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (e.matched()) {
      roundTrips(e, cloudOf(o.points), 20);  // warm-up: pools, first fragments
      const std::vector<double> full = roundTrips(e, cloudOf(o.points), o.samples);
      const std::vector<double> empty = roundTrips(e, cloudOf(0), o.samples);
      if (!full.empty() && !empty.empty()) {
        std::printf("transport: %s\n", o.profile.empty() ? "Fast DDS built-in (SHM + UDPv4)" : o.profile.c_str());
        std::printf("round trip, %d points (%d bytes): median %.3f ms, p90 %.3f ms\n", o.points, o.points * 16,
                    median(full), percentile(full, 0.9));
        std::printf("round trip, empty cloud: median %.3f ms, p90 %.3f ms\n", median(empty), percentile(empty, 0.9));
        std::printf("one way, %d points: %.3f ms (median round trip less half the empty one's)\n", o.points,
                    median(full) - median(empty) / 2);
        code = 0;
      } else {
        std::fprintf(stderr, "dds_transfer_bench: an answer did not come within 5 s\n");
      }
    } else {
      std::fprintf(stderr, "dds_transfer_bench: the two processes did not match within 20 s (domain %d)\n", o.domain);
    }
    Cloud stop = cloudOf(0);
    stop.header().frame_id("stop");
    e.writer->write(&stop);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  int status = 0;
  if (waitpid(child, &status, 0) < 0 || !WIFEXITED(status)) kill(child, SIGKILL);
  return code;
}
